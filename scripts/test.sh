#!/usr/bin/env bash
# hotmesh: build and run the whole test suite on a fresh Debian machine.
#   1. installs missing Debian packages (scripts/install-deps.sh),
#   2. builds Release with warnings as errors in build/ and runs every test with ctest,
#   3. builds with AddressSanitizer + UndefinedBehaviorSanitizer in build-asan/ and runs the
#      tests again,
#   4. builds the fuzz targets with clang in build-fuzz/ and runs each for 30 s, as many at
#      a time as there are cores (scripts/fuzz.sh, docs/fuzzing.md).
# Exits non-zero on any failure. Usage: scripts/test.sh [--no-sanitizers] [--no-fuzz]
set -euo pipefail
cd "$(dirname "$0")/.."

sanitizers=1
fuzz=1
for arg in "$@"; do
  case "$arg" in
    --no-sanitizers) sanitizers=0 ;;
    --no-fuzz) fuzz=0 ;;
    *) echo "usage: scripts/test.sh [--no-sanitizers] [--no-fuzz]" >&2; exit 2 ;;
  esac
done

# Each phase says when it starts, counted from the start of this script.
phase() { printf '== hotmesh [%d:%02d]: %s\n' $((SECONDS / 60)) $((SECONDS % 60)) "$1"; }

scripts/install-deps.sh
jobs=$(nproc)

phase "Release build (warnings are errors) and tests"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DHOTMESH_WERROR=ON
cmake --build build -j "$jobs"
ctest --test-dir build -j "$jobs" --output-on-failure --timeout 900

if ((sanitizers)); then
  phase "AddressSanitizer + UndefinedBehaviorSanitizer build and tests"
  # -O1 and line tables only (-g1: file and line in every report): instrumented code builds
  # in 60 % of the time of -g -O2. No benchmarks: they are timed in Release only.
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g1 -O1" \
        -DHOTMESH_WERROR=ON -DHOTMESH_SANITIZE=address,undefined -DHOTMESH_BENCH=OFF
  cmake --build build-asan -j "$jobs"
  # Full stacks for leak reports (OpenCASCADE is built without frame pointers), so the
  # suppressions can name the third-party function that keeps its memory on purpose; quiet
  # about them, since commands under test print JSON that the tests parse.
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1 \
  LSAN_OPTIONS=suppressions="$(pwd)/tests/lsan.supp":fast_unwind_on_malloc=0:print_suppressions=0 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir build-asan -j "$jobs" --output-on-failure --timeout 1800 -LE no_sanitizer
fi
if ((fuzz)); then
  # Two targets at a time on two cores; the seeds' short runs with the Release hotmesh.
  phase "fuzz targets"
  scripts/fuzz.sh -j "$jobs" --hotmesh build/app/hotmesh 30
fi
phase "all tests passed"
