#!/usr/bin/env bash
# hotmesh: build and run the whole test suite on a fresh Debian machine.
#   1. installs missing Debian packages (scripts/install-deps.sh),
#   2. builds Release with warnings as errors in build/ and runs every test with ctest (the
#      Python module's pytest tests and the installed package's consumer project among them),
#   3. builds with clang, AddressSanitizer + UndefinedBehaviorSanitizer, in build-sanitizers/:
#      the tests, hotmesh and the fuzz targets in one build, runs the tests again (but those
#      of tests/sanitizer_exclusions.txt, whose larger cases the Release build has run) and
#      each fuzz target for 10 s, as many at a time as there are cores (scripts/fuzz.sh,
#      docs/fuzzing.md).
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

if ((sanitizers || fuzz)); then
  phase "clang AddressSanitizer + UndefinedBehaviorSanitizer build: tests and fuzz targets"
  # One build for both: the libraries the fuzz targets read through carry libFuzzer's coverage
  # hooks too (CMakeLists.txt), the rest only the sanitizers. -O1 and line tables only (-g1:
  # file and line in every report); the tests' and the command line's own files at -O0
  # (tests/CMakeLists.txt, app/CMakeLists.txt). No benchmarks: they are timed in Release only;
  # no Python module: an interpreter cannot load an extension built with AddressSanitizer.
  cmake -S . -B build-sanitizers -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
        -DCMAKE_CXX_FLAGS_DEBUG="-g1 -O1" -DCGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE=ON \
        -DHOTMESH_WERROR=ON -DHOTMESH_FUZZ=ON -DHOTMESH_TESTS=$((sanitizers ? 1 : 0)) -DHOTMESH_BENCH=OFF \
        -DHOTMESH_PYTHON=OFF
  cmake --build build-sanitizers -j "$jobs"
fi
if ((sanitizers)); then
  phase "tests under the sanitizers"
  # Full stacks for leak reports (OpenCASCADE is built without frame pointers), so the
  # suppressions can name the third-party function that keeps its memory on purpose; quiet
  # about them, since commands under test print JSON that the tests parse.
  # The tests that the Release build runs on larger cases than the code needs are left out
  # (tests/sanitizer_exclusions.txt, each with its reason), as is the browser test (label
  # no_sanitizer: the page is the same; the service behind it runs here in test_app).
  left_to_release=$(grep -v -e '^#' -e '^$' tests/sanitizer_exclusions.txt | paste -sd '|')
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1 \
  LSAN_OPTIONS=suppressions="$(pwd)/tests/lsan.supp":fast_unwind_on_malloc=0:print_suppressions=0 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir build-sanitizers -j "$jobs" --output-on-failure --timeout 1800 -LE no_sanitizer \
          -E "$left_to_release"
fi
if ((fuzz)); then
  # Two targets at a time on two cores; the seeds' short runs with the Release hotmesh.
  phase "fuzz targets"
  scripts/fuzz.sh -j "$jobs" --build build-sanitizers --hotmesh build/app/hotmesh 10
fi
phase "all tests passed"
