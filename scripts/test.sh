#!/usr/bin/env bash
# README command 2: install what is missing, build, run the whole test suite (ctest).
#   scripts/test.sh [ctest args, e.g. -L physics]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
cd build
ctest --output-on-failure --timeout 900 "$@"
