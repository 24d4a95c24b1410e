#!/usr/bin/env bash
# Builds the libFuzzer targets (tools/fuzz/, clang -fsanitize=fuzzer,address, in build-fuzz/) and
# runs each for a bounded time on a seed corpus; exits non-zero when one crashed.
#   scripts/fuzz.sh [seconds per target, default 60] [target[:seconds] ...]
#   (targets: fuzz_options fuzz_mesh fuzz_table fuzz_option_pairs; by default all four, fuzz_table
#   and fuzz_option_pairs, the Python module's option dict, for a third of the time: a table is parsed
#   in microseconds, and the option pairs' parser after the insertion is fuzz_options')
# Needs clang and its runtime (apt-get install clang libclang-rt-14-dev; scripts/setup.sh does it);
# exits 77 (ctest: skipped) without clang. Environment:
#   FUZZ_DIR   where corpora, logs and crash inputs go (default build-fuzz/run)
# Seeds: the scenes of input/ (options, the Table 1 meshes swapped for a small one), the
# repository's meshes (meshes/cube_coarse.msh, beam_n2.msh, tests/data/*.msh, plus small ASCII
# meshes written by gmsh) and tables of time (inline and CSV, each shape fuzz_table asks for). A crash leaves its input as $FUZZ_DIR/<target>/crash-*; replay it with
#   build-fuzz/tools/fuzz/<target> <crash file>
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT="$(pwd)"
SECONDS_PER_TARGET="${1:-60}"
shift || true
TARGETS=("$@")
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=(fuzz_options fuzz_mesh "fuzz_table:$(((SECONDS_PER_TARGET + 2) / 3))" "fuzz_option_pairs:$((SECONDS_PER_TARGET / 3))")
NAMES=("${TARGETS[@]%%:*}")
FUZZ_DIR="${FUZZ_DIR:-$ROOT/build-fuzz/run}"

if ! command -v clang >/dev/null 2>&1; then
  echo "fuzz: clang not found (apt-get install clang libclang-rt-14-dev, or scripts/setup.sh): skipped" >&2
  exit 77
fi
scripts/make_meshes.sh
cmake -S . -B build-fuzz -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=Release -DFC_FUZZ=ON >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target "${NAMES[@]}" >/dev/null

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1
# leaks on error paths are not findings here (valgrind checks the normal runs); a huge
# allocation asked for by a malformed file (over 1.5 GB) comes back as NULL, which PETSc turns
# into an error, below libFuzzer's malloc limit (-rss_limit_mb) that would call it a crash
export ASAN_OPTIONS="detect_leaks=0:allocator_may_return_null=1:max_allocation_size_mb=1536"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"

seed_options() { # $1: corpus directory
  local f
  for f in input/*.opts input/hard/*.opts; do
    sed -e 's/#.*//' -e 's#meshes/\(table1_[0-9]*k\|beam_n16\|beam_n8\)\.msh#meshes/cube_coarse.msh#' "$f" |
      tr -s ' \n' ' ' >"$1/seed_$(basename "$(dirname "$f")")_$(basename "$f" .opts)"
  done
}

seed_pairs() { # $1: corpus directory; a few scenes of input/ as an option dict: "name<TAB>value" lines
  # (fuzz_options runs all of them through the same parser; here the seeds are the run's time)
  local f
  for f in input/cube_drop.opts input/finger_push.opts input/two_cubes.opts input/sliding.opts; do
    sed -e 's/#.*//' -e 's#meshes/\(table1_[0-9]*k\|beam_n16\|beam_n8\)\.msh#meshes/cube_coarse.msh#' "$f" |
      tr -s ' \n' '\n\n' | awk '/^-[A-Za-z]/ {if (n) print n; n = $0; next} n {print n "\t" $0; n = ""} END {if (n) print n}' \
        >"$1/seed_$(basename "$(dirname "$f")")_$(basename "$f" .opts)"
  done
  # a value with spaces, passed whole (a trajectory's rows after '; ')
  sed -e 's/#.*//' input/finger_push.opts | tr -s ' \n' '\n\n' | grep -v -e '^-tool_trajectory$' -e '^0:' |
    awk '/^-[A-Za-z]/ {if (n) print n; n = $0; next} n {print n "\t" $0; n = ""} END {if (n) print n}' \
      >"$1/seed_spaced_trajectory"
  printf -- '-tool_trajectory\t0:0.03,0,0.08; 0.5:0.0195,0,0.08; 1.0:0.0,0,0.08\n-time_steps\t2\n' >>"$1/seed_spaced_trajectory"
}

seed_mesh() { # $1: corpus directory
  local f tmp
  for f in meshes/cube_coarse.msh meshes/beam_n2.msh tests/data/*.msh; do
    cp "$f" "$1/seed_$(basename "$f")"
  done
  tmp="$(mktemp -d)"
  for fmt in msh22 msh41; do
    (cd meshes && gmsh -3 -nt 1 -setnumber lc 0.6 -format "$fmt" cube.geo -o "$tmp/cube_$fmt.msh" >/dev/null 2>&1) &&
      cp "$tmp/cube_$fmt.msh" "$1/seed_ascii_cube_$fmt.msh" || true
  done
  rm -rf "$tmp"
}

seed_table() { # $1: corpus directory; the first byte chooses the table's shape (tools/fuzz/fuzz_table.c)
  printf '\0000:0,0,0;1:0.3,0,0.5' >"$1/seed_trajectory_inline"
  printf '\000t,x,y,z,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n1,0.3,0,0.5,0,0,0,1\n' >"$1/seed_trajectory_csv"
  printf '\001t,ux,uy,uz\n# a comment\n0,0,0,0\r\n0.5,0,0,-0.01\r\n1,0,0,-0.02\r\n' >"$1/seed_displacement_csv"
  printf '\0010:0,0,0;1:0,0,-100' >"$1/seed_force_inline"
  printf '\0020:0;1:1e5' >"$1/seed_pressure_inline"
  printf '\003t,a,b\n0,1,2\n1,3,4\n' >"$1/seed_any_csv"
}

# A crash input is replayed alone for its stack. One whose stack reaches PETSc's gmsh reader
# (DMPlexCreateGmsh...) with no frame of fecontact's own code above it (a frame whose source file,
# " $ROOT/...c:line", is in this repository; PETSc's, libc's and the interceptors' frames have
# none, and libc's name glibc's sources when libc6-dbg is installed) is PETSc 3.18's own reader
# failing or looping on a malformed file: kept, not counted against fecontact (see
# docs/reliability.md). One that does not crash again alone is listed as unreproducible: it
# depended on an earlier input of the same process (PETSc, not instrumented, can corrupt memory
# silently; fecontact's own errors are instrumented and reproduce). Any other one is a finding in
# fecontact and fails the run.
RUNTIME='__asan|__interceptor|__sanitizer|fuzzer::|posix_memalign|[^_]malloc|calloc|realloc|libc\.so|libc_start'
classify() { # $1: target binary, $2: crash input; prints "petsc-gmsh <frame>" or "fecontact <frame>"
  local report frames n top
  report="$(TMPDIR="$dir/tmp" timeout 300 "$1" -rss_limit_mb=4096 -timeout=60 -runs=1 "$2" 2>&1 || true)"
  printf '%s\n' "$report" >"$2.txt"
  # the first stack without the sanitizer's, libFuzzer's and libc's own frames
  frames="$(awk '/^ +#[0-9]+ /{s=1; print; next} s{exit}' <<<"$report" | grep -vE "$RUNTIME" || true)"
  top="$(head -n 1 <<<"$frames" | sed -E 's/^ +#[0-9]+ 0x[0-9a-f]+ (in )?//; s/ \(BuildId.*//')"
  n="$(grep -n 'Gmsh.*libpetsc' <<<"$frames" | head -n 1 | cut -d: -f1)"
  if [ -n "$n" ] && ! head -n $((n - 1)) <<<"$frames" | grep -qF " $ROOT/"; then
    echo "petsc-gmsh ${top:-?}"
  elif [ -z "$frames" ]; then
    echo "unreproducible"
  else
    echo "fecontact $top"
  fi
}

status=0
for spec in "${TARGETS[@]}"; do
  t="${spec%%:*}"
  seconds="$SECONDS_PER_TARGET"
  [ "$spec" = "$t" ] || seconds="${spec#*:}"
  dir="$FUZZ_DIR/$t"
  bin="$ROOT/build-fuzz/tools/fuzz/$t"
  mkdir -p "$dir/corpus" "$dir/seeds"
  rm -rf "$dir"/crash-* "$dir"/oom-* "$dir"/timeout-* "$dir"/leak-* "$dir/petsc-reader"
  mkdir -p "$dir/petsc-reader"
  export FUZZ_PETSC_CRASHES="$dir/petsc-reader" # fuzz_mesh keeps the inputs that crash PETSc's reader
  case "$t" in
    fuzz_options) seed_options "$dir/seeds"; extra=(-dict="$ROOT/tools/fuzz/options.dict" -max_len=4096) ;;
    fuzz_option_pairs) seed_pairs "$dir/seeds"; extra=(-dict="$ROOT/tools/fuzz/options.dict" -max_len=4096) ;;
    fuzz_mesh) seed_mesh "$dir/seeds"; extra=(-max_len=65536) ;;
    fuzz_table) seed_table "$dir/seeds"; extra=(-max_len=65536) ;;
    *) echo "fuzz: unknown target $t" >&2; exit 2 ;;
  esac
  echo "fuzz: $t for ${seconds} s (log $dir/log.txt)"
  start=$(date +%s)
  set +e
  # fork mode: the campaign goes on after a crash (each is saved and classified below); from the
  # repository root, as the seeds name meshes by relative paths
  mkdir -p "$dir/tmp" # the targets' scratch files and libFuzzer's fork directory
  TMPDIR="$dir/tmp" "$bin" -fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1 -max_total_time="$seconds" \
    -timeout=60 -rss_limit_mb=4096 -close_fd_mask=1 -artifact_prefix="$dir/" "${extra[@]}" \
    "$dir/corpus" "$dir/seeds" >"$dir/log.txt" 2>&1
  rc=$?
  set -e
  execs=$(grep -oE '^#[0-9]+' "$dir/log.txt" | tail -n 1 | tr -d '#')
  cov=$(grep -oE "cov: [0-9]+" "$dir/log.txt" | tail -n 1 || true)
  nours=0
  npetsc=0
  nunrep=0
  for f in "$dir"/crash-* "$dir"/oom-* "$dir"/timeout-* "$dir"/leak-*; do
    [ -e "$f" ] && [[ "$f" != *.txt ]] || continue
    kind="$(classify "$bin" "$f")"
    case "$kind" in
      petsc-gmsh*) npetsc=$((npetsc + 1)) ;;
      unreproducible) nunrep=$((nunrep + 1)); echo "  unreproducible crash (not counted)  input: $f" ;;
      *) nours=$((nours + 1)); echo "  CRASH $kind  input: $f (report: $f.txt)" ;;
    esac
  done
  rm -rf "$dir/tmp"
  # inputs that crashed PETSc's reader in fuzz_mesh's forked pre-read (skipped, not findings)
  npre=$(ls "$dir/petsc-reader" | wc -l)
  echo "fuzz: $t: exit $rc, $(($(date +%s) - start)) s, ${execs:-0} runs, ${cov:-cov: ?}," \
    "corpus $(ls "$dir/corpus" | wc -l) inputs, $nours crashes in fecontact ($nunrep unreproducible);" \
    "PETSc's gmsh reader crashed on $((npre + npetsc)) inputs (kept in $dir/petsc-reader)"
  for f in "$dir"/crash-* "$dir"/oom-*; do # the ones classified as PETSc's, beside the others
    [ -e "$f" ] && [[ "$f" != *.txt ]] && grep -q Gmsh "$f.txt" 2>/dev/null && mv "$f" "$f.txt" "$dir/petsc-reader/"
  done
  if [ "$nours" -gt 0 ] || { [ "$rc" -ne 0 ] && [ $((npetsc + nunrep)) -eq 0 ]; }; then
    status=1
    [ "$nours" -gt 0 ] || tail -n 30 "$dir/log.txt" >&2
  fi
done
exit $status
