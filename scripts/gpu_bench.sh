#!/usr/bin/env bash
# GPU runs: host types against CUDA types with today's
# default builder (condensed), a co-rotational body (A refactored every step) and 2 MPI ranks
# (mpiaijcusparse); results in docs/gpu.md. Run on the GPU machine from the repository root, with .gpu carried (the bundle of
# `scripts/gpu_build.sh build`, which packs the meshes these runs read):
#
#   bash scripts/gpu_bench.sh [OUTDIR]
#
# Prints, per run, fecontact's own summary (wall of the time-step loop and time per phase), then
# the largest differences of each CUDA run's final positions and contact forces from its host twin
# (python3 with h5py: the GPU machine's). Logs go to OUTDIR (default /tmp/gpu_bench).
set -uo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
OUTDIR="${1:-/tmp/gpu_bench}"
mkdir -p "$OUTDIR"
R=/tmp/fcgpu
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1
run() { # name, ranks, args...: fecontact through the bundle; output out/<name>.h5 under $R
  local name=$1 np=$2
  shift 2
  echo "=== $name (np $np): $*"
  if [ "$np" = 1 ]; then
    bash "$ROOT/scripts/gpu_build.sh" run "$@" -output_file "out/$name.h5" -output_every 1 >"$OUTDIR/$name.log" 2>&1
  else
    mpirun -n "$np" --bind-to core bash "$ROOT/scripts/gpu_build.sh" run "$@" -output_file "out/$name.h5" \
      -output_every 1 >"$OUTDIR/$name.log" 2>&1
  fi
  echo "exit $?"
  grep -E "steps of|time per phase|Newton|error|Error" "$OUTDIR/$name.log" | head -8
}
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader
lscpu | grep -E "Model name|^CPU\(s\)"
echo "fecontact commit: $(cat "$ROOT/.gpu/fecontact-src.commit")"

# unpack once (run_device unpacks on first use): the 2-rank runs must not both unpack
bash "$ROOT/scripts/gpu_build.sh" run -help >/dev/null 2>&1 || true
[ -f "$R/meshes/cube_18.msh" ] || echo "the bundle has no meshes/cube_18.msh (built before it was packed): the cube runs will fail"

BOX_CUDA="-box_dm_mat_type aijcusparse -box_dm_vec_type cuda -wh_mat_type seqdensecuda -frames_mat_type seqaijcusparse -contact_vec_type seqcuda -use_gpu_aware_mpi 0"
CUBE_CUDA="${BOX_CUDA//-box_/-cube_}"
T18="-options_file input/table1_18k.opts -time_steps 3 -constraint_scheme fast"
T36="-options_file input/table1_36k.opts -time_steps 2 -constraint_scheme fast"
CUBE="-options_file input/cube_rest.opts -time_steps 5 -constraint_scheme fast"

run t18_host 1 $T18
run t18_cuda 1 $T18 $BOX_CUDA
run t18_host_redundant 1 $T18 -compliance_type redundant
run t18_cuda_redundant 1 $T18 $BOX_CUDA -compliance_type redundant
run t36_host 1 $T36
run t36_cuda 1 $T36 $BOX_CUDA
run cube_host 1 $CUBE
run cube_cuda 1 $CUBE $CUBE_CUDA
run t18_host_np2 2 $T18
run t18_cuda_np2 2 $T18 $BOX_CUDA
run cube_host_np2 2 $CUBE
run cube_cuda_np2 2 $CUBE $CUBE_CUDA

python3 - "$R/out" <<'EOF'
import sys, h5py, numpy as np
out = sys.argv[1]
pairs = [("t18_cuda", "t18_host"), ("t18_cuda_redundant", "t18_host_redundant"), ("t36_cuda", "t36_host"),
         ("cube_cuda", "cube_host"), ("t18_cuda_np2", "t18_host_np2"), ("cube_cuda_np2", "cube_host_np2"),
         ("t18_host_np2", "t18_host"), ("cube_host_np2", "cube_host")]
for a, b in pairs:
    try:
        fa, fb = h5py.File(f"{out}/{a}.h5", "r"), h5py.File(f"{out}/{b}.h5", "r")
    except OSError as e:
        print(f"{a} vs {b}: cannot open ({e})")
        continue
    body = [k for k in fa["bodies"] if k != "ground"][0]
    def pos(h):  # in an order independent of the partition: by reference position
        ref, p = h[f"bodies/{body}/mesh/reference"][:], h[f"bodies/{body}/positions"][-1]
        return p[np.lexsort(np.round(ref, 9).T[::-1])]
    pa, pb = pos(fa), pos(fb)
    ua = fa[f"bodies/{body}/displacement"][-1]
    Fa, Fb = fa["contacts/force"][:], fb["contacts/force"][:]
    same = Fa.shape == Fb.shape
    dF = np.abs(Fa - Fb).max() / max(np.abs(Fb).max(), 1e-300) if same else float("nan")
    print(f"{a} vs {b}: final positions max |diff| {np.abs(pa - pb).max():.2e} m (max |u| {np.abs(ua).max():.2e} m); "
          f"contact records {len(Fa)} vs {len(Fb)}; forces max |diff| / max |F| {dF:.2e}; "
          f"pgs sweeps {list(fa['steps/pgs_iterations'][:])} vs {list(fb['steps/pgs_iterations'][:])}")
EOF
