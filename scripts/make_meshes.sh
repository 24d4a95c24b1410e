#!/usr/bin/env bash
# Generates the fecontact gmsh meshes (.msh, format 4.1 binary, linear tetrahedra) from the
# .geo sources in meshes/. Usage: scripts/make_meshes.sh [OUTDIR]   (default: <repo>/meshes)
#
# A mesh is regenerated only when its .msh is missing or older than its .geo or this script
# (the per-mesh parameters live here), so repeated calls are cheap. Quiet unless something
# fails; exits non-zero naming the failed mesh(es). Deterministic: gmsh runs single-threaded.
# Environment: GMSH (default: gmsh), FORCE=1 regenerates everything.
set -euo pipefail

SCRIPT="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/$(basename "${BASH_SOURCE[0]}")"
GEODIR="$(cd "$(dirname "$SCRIPT")/../meshes" && pwd)"
OUTDIR="${1:-$GEODIR}"
GMSH="${GMSH:-gmsh}"
FORCE="${FORCE:-0}"

if ! command -v "$GMSH" >/dev/null 2>&1; then
  echo "make_meshes: gmsh not found (install it: scripts/setup.sh)" >&2
  exit 1
fi
mkdir -p "$OUTDIR"
OUTDIR="$(cd "$OUTDIR" && pwd)"

# name  geo  gmsh -setnumber parameters
MESHES=(
  "cube         cube.geo      lc 0.08"
  "cube_coarse  cube.geo      lc 0.2"
  "cube_medium  cube.geo      lc 0.12"
  "cube_015     cube.geo      lc 0.15"
  "beam_n2      beam.geo      n 2"
  "beam_n4      beam.geo      n 4"
  "beam_n8      beam.geo      n 8"
  "beam_n16     beam.geo      n 16"
  "cylinder     cylinder.geo  lc 0.07"
  "sphere       sphere.geo    lc 0.075"
  "sphere_coarse sphere.geo   lc 0.2"
  "ball_5cm     sphere.geo    r 0.05 lc 0.015"
  "hollow_sphere  hollow_sphere.geo  lc 0.1"
  "hollow_sphere_fine  hollow_sphere.geo  lc 0.05"
  "finger       finger.geo    lc 0.004"
  "finger_fold  finger_fold.geo  lc 0.005 lc_joint 0.0035 r 0.0025"
  "slab         slab.geo      lc 0.125"
  "table1_18k   table1.geo    nx 20 ny 20 nz 15 d 0.05"
  "table1_24k   table1.geo    nx 20 ny 19 nz 21 d 0.05"
  "table1_30k   table1.geo    nx 20 ny 20 nz 25 d 0.05"
  "table1_36k   table1.geo    nx 24 ny 20 nz 25 d 0.05"
  "cube_18      table1.geo    nx 18 ny 18 nz 18 d 0.0588235294117647"
  "cube_18_20cm table1.geo    nx 18 ny 18 nz 18 d 0.011764705882352941"
  "thin_slab    table1.geo    nx 16 ny 16 nz 2 d 0.02"
  "small_cube   table1.geo    nx 4 ny 4 nz 4 d 0.05"
  "cube_6       table1.geo    nx 6 ny 6 nz 6 d 0.03"
  "soft_slab    table1.geo    nx 13 ny 13 nz 5 d 0.025"
  "heavy_block  table1.geo    nx 7 ny 7 nz 9 d 0.05"
  "foam_board   table1.geo    nx 7 ny 7 nz 2 d 0.05"
  "six_tets     table1.geo    nx 2 ny 2 nz 2 d 0.2"
  "slide_slab_coarse table1.geo nx 21 ny 7 nz 2 d 0.05"
  "slide_slab   table1.geo    nx 41 ny 13 nz 3 d 0.025"
  "slide_slab_fine table1.geo nx 81 ny 25 nz 5 d 0.0125"
  "bar          table1.geo    nx 12 ny 3 nz 3 d 0.05"
  "u_bar        table1.geo    nx 41 ny 5 nz 3 d 0.025"
  "sheet        table1.geo    nx 49 ny 9 nz 2 d 0.025"
  "membrane     table1.geo    nx 21 ny 21 nz 2 d 0.025 dz 0.02"
  "sheet_coarse table1.geo    nx 37 ny 7 nz 2 d 0.03333333333333333 dz 0.025"
  "hertz_sphere_1  hertz_sphere.geo  lc_min 0.04"
  "hertz_sphere_2  hertz_sphere.geo  lc_min 0.02"
  "hertz_sphere_3  hertz_sphere.geo  lc_min 0.01"
  "hertz_block_1   hertz_block.geo   lc_min 0.04"
  "hertz_block_2   hertz_block.geo   lc_min 0.02"
  "hertz_block_3   hertz_block.geo   lc_min 0.01"
  "punch_block     punch_block.geo   d 0.008"
  "punch_block_free punch_block_free.geo lc_min 0.008"
)

failed=()
for entry in "${MESHES[@]}"; do
  read -r name geo params <<<"$entry"
  src="$GEODIR/$geo"
  out="$OUTDIR/$name.msh"
  if [ "$FORCE" != 1 ] && [ -f "$out" ] && [ "$out" -nt "$src" ] && [ "$out" -nt "$SCRIPT" ]; then
    continue
  fi
  setargs=()
  read -r -a kv <<<"${params:-}"
  for ((i = 0; i + 1 < ${#kv[@]}; i += 2)); do
    setargs+=(-setnumber "${kv[i]}" "${kv[i + 1]}")
  done
  tmp="$OUTDIR/.$name.tmp$$.msh"
  log="$OUTDIR/.$name.tmp$$.log"
  # run from the .geo directory so relative includes would resolve; write to a temp file and
  # rename, so an interrupted or failed run never leaves a fresh-looking partial .msh
  if (cd "$GEODIR" && "$GMSH" -3 -nt 1 -format msh41 -bin "${setargs[@]}" "$src" -o "$tmp") >"$log" 2>&1 &&
    ! grep -q "^Error" "$log" && [ -s "$tmp" ] && grep -aq '^\$EndElements' "$tmp"; then
    mv -f "$tmp" "$out"
    rm -f "$log"
  else
    echo "make_meshes: FAILED to generate $name.msh from $geo ($params); gmsh output:" >&2
    sed 's/^/  /' "$log" | grep -E "Error|Warning" >&2 || tail -n 20 "$log" | sed 's/^/  /' >&2
    rm -f "$tmp" "$log"
    failed+=("$name")
  fi
done

if [ ${#failed[@]} -gt 0 ]; then
  echo "make_meshes: failed: ${failed[*]}" >&2
  exit 1
fi
