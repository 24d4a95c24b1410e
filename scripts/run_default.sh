#!/usr/bin/env bash
# README command 1: install what is missing, build, run the default scene, draw it (plots, and the
# scene with ParaView unless FC_SKIP_PARAVIEW=1).
#   scripts/run_default.sh [NRANKS] [extra fecontact options]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
NP="${1:-2}"; shift || true
mkdir -p out
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1
mpirun -n "$NP" --oversubscribe build/fecontact -options_file input/default.opts "$@"
/usr/bin/python3 scripts/plot_run.py out/default.h5 -o out/default.png
if [ "${FC_SKIP_PARAVIEW:-0}" != "1" ]; then
  xvfb-run -a pvbatch scripts/render.py out/default.xmf --field velocity --time 0.5 --arrow-length 0.06 -o out/default_scene.png
fi
