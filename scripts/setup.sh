#!/usr/bin/env bash
# Installs the Debian packages fecontact needs, only those missing. Idempotent; run as root
# (or with sudo available). Usage: scripts/setup.sh
# ParaView (paraview, python3-paraview: pvbatch) and xvfb (xvfb-run: a display for pvbatch on a
# headless machine) draw the output (scripts/render.py, README command 1) and are what
# tests/test_paraview.py reads it with; FC_SKIP_PARAVIEW=1 installs neither (that test then skips,
# README command 1 draws no scene picture). pip, setuptools and wheel: `pip install ./python`
# (docs/python.md), which tests/test_python.py does.
set -euo pipefail

PKGS=(
  build-essential cmake pkg-config clang-format valgrind clang libclang-rt-14-dev
  petsc-dev libmumps-dev libscalapack-openmpi-dev libmetis-dev libhdf5-openmpi-dev openmpi-bin libopenmpi-dev
  libopenblas0-pthread gmsh
  python3-petsc4py python3-h5py python3-matplotlib python3-numpy python3-siconos
  python3-pip python3-setuptools python3-wheel
)
if [ "${FC_SKIP_PARAVIEW:-0}" != "1" ]; then
  PKGS+=(paraview python3-paraview xvfb)
fi

missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  echo "setup: all packages present"
fi
