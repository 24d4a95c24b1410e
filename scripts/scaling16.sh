#!/usr/bin/env bash
# Strong and weak scaling on the 16-core GPU machine (docs/scaling.md, "16 cores"), with the bundle
# of `scripts/gpu_build.sh build` (host matrix types: this is the CPU study; scripts/gpu_bench.sh
# is the CUDA one). Run from the repository root on that machine, with .gpu carried:
#
#   bash scripts/scaling16.sh [OUTDIR] [RANKS]      (RANKS default "1 2 4 8 16")
#
# A dry run here (host build, oversubscribed ranks: correctness and memory, not speed):
#   FCEXE=build/fecontact bash scripts/scaling16.sh /tmp/s16 "1 2 4"
#
# Scenes (fast scheme, default builder `condensed`, 3 steps, 5 Newton iterations):
#   strong: the 36k Table 1 box (480 contacts) and the 149k box (1600 contacts; its mesh is
#           .gpu/table1_150k.msh, made here by scripts/scaling.py's gmsh command, since the bundle
#           packs only the Table 1 meshes) on every RANKS;
#   weak:   about 18k DOFs per rank: the 18k box on 1 rank, the 36k box on 2, the 149k box on 8.
# Per run: the step (mean of /steps/wall_time), the set-up (wall minus steps), the phases (means of
# /steps/timing, the largest rank), PETSc's -memory_view peak process memory (max over ranks and
# total), and the final positions against the 1-rank run of the same scene (relative, in an order
# independent of the partition). Writes OUTDIR/scaling16.md (a markdown table) and the logs.
set -uo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
OUTDIR="${1:-/tmp/scaling16}"
RANKS="${2:-1 2 4 8 16}"
mkdir -p "$OUTDIR"
R=/tmp/fcgpu
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1
lscpu | grep -E "Model name|^CPU\(s\)|Thread|Core"
echo "fecontact commit: $(cat "$ROOT/.gpu/fecontact-src.commit" 2>/dev/null)"
if [ -n "${FCEXE:-}" ]; then # a dry run with a host build: FCEXE=build/fecontact, oversubscribed
  R="$ROOT"
  EXE=("$FCEXE")
  MPI=(mpirun --oversubscribe)
  M150="$ROOT/.gpu/table1_150k.msh"
else
  bash "$ROOT/scripts/gpu_build.sh" run -help >/dev/null 2>&1 || true # unpack once
  cp "$ROOT/.gpu/table1_150k.msh" "$R/meshes/"
  EXE=(bash "$ROOT/scripts/gpu_build.sh" run)
  MPI=(mpirun --bind-to core --map-by core)
  M150=meshes/table1_150k.msh
fi
mkdir -p "$R/out"
COMMON="-options_file input/table1_36k.opts -time_steps 3 -output_every 3 -constraint_scheme fast -newton_max_it 5 -memory_view"
run() { # tag, ranks, args...
  local tag=$1 np=$2
  shift 2
  local t0 t1
  t0=$(date +%s%N)
  (cd "$R" && "${MPI[@]}" -n "$np" "${EXE[@]}" $COMMON "$@" -output_file "out/$tag.h5" >"$OUTDIR/$tag.log" 2>&1)
  local rc=$?
  t1=$(date +%s%N)
  local wall=$(((t1 - t0) / 1000000)) # ms (no bc on the GPU machine)
  echo "$tag $np $rc $wall" >>"$OUTDIR/runs.txt"
  echo "=== $tag np $np: exit $rc, $wall ms"
}
rm -f "$OUTDIR/runs.txt"
for np in $RANKS; do run "s36k_np$np" "$np"; done
for np in $RANKS; do run "s150k_np$np" "$np" -box_dm_plex_filename "$M150"; done
run w18k_np1 1 -box_dm_plex_filename meshes/table1_18k.msh
# the 36k on 2 and the 149k on 8 are the strong runs' own

"${PY:-python3}" - "$OUTDIR" "$R/out" <<'EOF'
import re, sys, h5py, numpy as np
outdir, h5dir = sys.argv[1], sys.argv[2]
PH = ["assembly", "factorization", "free_motion", "collision", "compliance", "contact_solver", "correction", "rebuild_w", "proximity_update"]
runs = [l.split() for l in open(f"{outdir}/runs.txt")]
def positions(tag):
    h = h5py.File(f"{h5dir}/{tag}.h5", "r")
    ref, pos = h["bodies/box/mesh/reference"][:], h["bodies/box/positions"][-1]
    o = np.lexsort(np.round(ref, 9).T[::-1])
    return pos[o]
rows = ["| kind | scene | ranks | contacts | step (s) | set-up (s) | " + " | ".join(PH) + " | peak mem max rank (MB) | peak mem total (MB) | vs 1 rank |",
        "|---|---|---:|---:|---:|---:|" + "---:|" * len(PH) + "---:|---:|---:|"]
for tag, np_, rc, wall_ms in runs:
    wall = float(wall_ms) / 1000.0
    scene = tag.split("_")[0][1:]
    kind = "weak" if tag[0] == "w" else "strong"
    if rc != "0":
        rows.append(f"| {kind} | {scene} | {np_} | failed (exit {rc}) |")
        continue
    h = h5py.File(f"{h5dir}/{tag}.h5", "r")
    s = h["steps"]
    step = float(s["wall_time"][:].mean())
    nsteps = len(s["wall_time"][:])
    per = [float(s["timing/" + p][:].mean()) for p in PH]
    log = open(f"{outdir}/{tag}.log").read()
    m = re.search(r"Maximum \(over computational time\) process memory:\s+total\s+(\S+)\s+max\s+(\S+)", log)
    tot, mx = (float(m.group(1)) / 2**20, float(m.group(2)) / 2**20) if m else (float("nan"),) * 2
    ref = f"s{scene}_np1" if kind == "strong" else None
    d = "-"
    if ref and ref != tag:
        try:
            a, b = positions(tag), positions(ref)
            d = "%.1e" % (np.abs(a - b).max() / np.abs(b).max())
        except Exception as e:
            d = "n/a"
    rows.append(f"| {kind} | {scene} | {np_} | {int(s['contacts'][-1])} | {step:.3f} | {wall - step * nsteps:.2f} | "
                + " | ".join("%.3f" % x for x in per) + f" | {mx:.0f} | {tot:.0f} | {d} |")
open(f"{outdir}/scaling16.md", "w").write("\n".join(rows) + "\n")
print("\n".join(rows))
EOF
