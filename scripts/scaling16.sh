#!/usr/bin/env bash
# Strong and weak scaling on the 16-core GPU machine (docs/scaling.md, "16 cores"), with the bundle
# of `scripts/gpu_build.sh build` (host matrix types: this is the CPU study; scripts/gpu_bench.sh
# is the CUDA one). Run from the repository root on that machine, with .gpu carried:
#
#   bash scripts/scaling16.sh [OUTDIR] [RANKS]      (RANKS default "1 2 4 8 16")
#
# A dry run here (host build, oversubscribed ranks: correctness and memory, not speed):
#   FCEXE=build/fecontact bash scripts/scaling16.sh /tmp/s16 "1 2 4"
# (FCLARGE=0 leaves out the large box: scripts/memory_ranks.py --scene large measures it here).
# The large box runs on LARGE_RANKS (default "4 8 16"): its 1-rank run alone takes 7-8 minutes
# (one factorization with a 13k-DOF Schur block and C's inversion on one core), the whole budget.
#
# Scenes (fast scheme, default builder `condensed`, 3 steps, 5 Newton iterations; the large scene
# 1 step, 2 Newton iterations), every one with the default thresholds of the distributed contact
# phase (W_H by rows from 1000 contacts, Sigma / C distributed from a 3000-DOF Schur block):
#   strong: the 36k Table 1 box (480 contacts), the 149k box (1600 contacts) and the large box of
#           input/large_box.opts (245,760 DOFs, 4096 contacts) on every RANKS; the meshes of the
#           last two are .gpu/table1_150k.msh and .gpu/large_box.msh, made here by
#           scripts/scaling.py's and scripts/memory_ranks.py's gmsh commands (the bundle packs only
#           the Table 1 meshes), or by gmsh there if it has one;
#   weak:   18k DOFs and 400 contacts per rank: boxes of nx x ny x 15 vertices with nx ny = 400 p
#           (20 x 20 on 1 rank, 28 x 29 on 2, 40 x 40 on 4, 56 x 57 on 8, 80 x 80 on 16), meshes
#           .gpu/weak_p<P>.msh made like the others (a rank count whose mesh is missing is skipped).
# Per run: the step (mean of /steps/wall_time), the set-up (wall minus steps), the phases (means of
# /steps/timing, the largest rank), PETSc's -memory_view peak process memory (max over ranks and
# total), /memory's contact data of the largest rank (W_H + W_k + W_b + Sigma) and MUMPS' factor
# (INFO(22)), and the final positions against the 1-rank run of the same scene (relative, in an order
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
  MDIR="$ROOT/.gpu"
else
  bash "$ROOT/scripts/gpu_build.sh" run -help >/dev/null 2>&1 || true # unpack once
  cp "$ROOT/.gpu/table1_150k.msh" "$R/meshes/"
  EXE=(bash "$ROOT/scripts/gpu_build.sh" run)
  MPI=(mpirun --bind-to core --map-by core)
  M150=meshes/table1_150k.msh
  for m in "$ROOT"/.gpu/large_box.msh "$ROOT"/.gpu/weak_p*.msh; do [ -f "$m" ] && cp "$m" "$R/meshes/"; done
  MDIR="$R/meshes"
fi
mesh() { # name nx ny nz: MDIR/name.msh, by gmsh where it is missing and gmsh exists
  [ -f "$MDIR/$1.msh" ] || ! command -v gmsh >/dev/null ||
    gmsh -3 -nt 1 -format msh41 -bin -setnumber nx "$2" -setnumber ny "$3" -setnumber nz "$4" -setnumber d 0.05 \
      "$ROOT/meshes/table1.geo" -o "$MDIR/$1.msh" >/dev/null
  [ -f "$MDIR/$1.msh" ]
}
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
if [ "${FCLARGE:-1}" = 0 ]; then echo "=== large box skipped (FCLARGE=0)"
elif mesh large_box 64 64 20; then
  for np in ${LARGE_RANKS:-4 8 16}; do
    run "slarge_np$np" "$np" -time_steps 1 -output_every 1 -newton_max_it 2 -box_dm_plex_filename "$MDIR/large_box.msh" \
      -ground_length 5
  done
else echo "=== large box skipped: no $MDIR/large_box.msh and no gmsh"; fi
declare -A WNX=([1]=20 [2]=28 [4]=40 [8]=56 [16]=80) WNY=([1]=20 [2]=29 [4]=40 [8]=57 [16]=80)
for np in $RANKS; do
  if [ -n "${WNX[$np]:-}" ] && mesh "weak_p$np" "${WNX[$np]}" "${WNY[$np]}" 15; then
    run "wp${np}_np$np" "$np" -box_dm_plex_filename "$MDIR/weak_p$np.msh" -ground_length 5
  else echo "=== weak run on $np ranks skipped (no mesh)"; fi
done

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
rows = ["| kind | scene | ranks | contacts | step (s) | set-up (s) | " + " | ".join(PH) + " | peak mem max rank (MB) | peak mem total (MB) | contact data max rank (MB) | MUMPS factor max rank (MB) | vs 1 rank |",
        "|---|---|---:|---:|---:|---:|" + "---:|" * len(PH) + "---:|---:|---:|---:|---:|"]
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
    if scene == "large":
        ref = min((t for t, n, r, w in runs if t.startswith("slarge_") and r == "0"), key=lambda t: int(t.split("np")[1]), default=None)
    d = "-"
    if ref and ref != tag:
        try:
            a, b = positions(tag), positions(ref)
            d = "%.1e" % (np.abs(a - b).max() / np.abs(b).max())
        except Exception as e:
            d = "n/a"
    mem = h["memory"][:] if "memory" in h else np.full((1, 7), np.nan)  # columns: peak_rss,W_H,W_k,W_b,Sigma,factor,contact_data
    data, fac = mem[:, 6].max() / 2**20, mem[:, 5].max() / 2**20
    rows.append(f"| {kind} | {scene} | {np_} | {int(s['contacts'][-1])} | {step:.3f} | {wall - step * nsteps:.2f} | "
                + " | ".join("%.3f" % x for x in per) + f" | {mx:.0f} | {tot:.0f} | {data:.0f} | {fac:.0f} | {d} |")
open(f"{outdir}/scaling16.md", "w").write("\n".join(rows) + "\n")
print("\n".join(rows))
EOF
