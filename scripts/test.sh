#!/usr/bin/env bash
# README command 2: install what is missing, build, run the whole test suite (ctest), then the
# same suite again on an AddressSanitizer + UndefinedBehaviorSanitizer build (build-asan/,
# -DFC_SANITIZE=address,undefined; docs/reliability.md).
#   scripts/test.sh [ctest args, e.g. -L physics]     (the arguments apply to both runs)
# FC_TEST_SANITIZE=0 skips the sanitized run.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
scripts/build.sh
(cd build && ctest --output-on-failure --timeout 900 -j"$(nproc)" "$@")
if [ "${FC_TEST_SANITIZE:-1}" != 0 ]; then
  echo "test: the suite again under AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/)"
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DFC_SANITIZE=address,undefined >/dev/null
  cmake --build build-asan -j"$(nproc)"
  (cd build-asan && ctest --output-on-failure --timeout 900 -j"$(nproc)" "$@")
fi
