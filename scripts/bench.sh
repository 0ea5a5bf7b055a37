#!/usr/bin/env bash
# hotmesh: build Release in build/ (warnings are errors) and run every benchmark, bench/bench_*,
# printing the machine, the load and each benchmark's Markdown tables; docs/performance.md
# records the results. Benchmarks are not tests: ctest never runs them.
#
# Usage: scripts/bench.sh [--quick | --paper-size | --busy]
#   --quick        small sizes only (a smoke run of a minute, numbers not worth recording)
#   --busy         only hotmesh deform beside processes that keep the cores busy, default threads
#                  against one thread, and two threads against one at 200 000 cells, idle
#                  (bench_busy; about ten minutes)
#   --paper-size   only the paper's stator-well sector (section 6.1): 2.7 million hexes, sliding,
#                  16 increments, `linear: auto` (amg at this size) with the Eisenstat-Walker
#                  forcing term, two ranks of one thread with PETSc's lean triple products
#                  (docs/parallel-runs.md): time per phase, CG iterations, peak memory of both
#                  ranks and quality (bench_stator_solve). 14 to 18 minutes and 11.8 GiB.
# A full run takes about twenty-five minutes on 2 cores (most of it the stator-well sector solved
# at 50 000 cells, and both linear solvers on the stator-well sample) and needs about 5 GB of
# memory (the 100^3 hex block's element matrices). Run it on an otherwise idle machine: the load is printed
# before and after each benchmark and the tables report, row by row, how many cores other
# processes kept busy ("other load"); medians resist short disturbances, not a busy machine.
set -euo pipefail
cd "$(dirname "$0")/.."

quick=0
paper=0
busy_only=0
for arg in "$@"; do
  case "$arg" in
    --quick) quick=1 ;;
    --paper-size) paper=1 ;;
    --busy) busy_only=1 ;;
    *) echo "usage: scripts/bench.sh [--quick | --paper-size | --busy]" >&2; exit 2 ;;
  esac
done

benches=()
for source in bench/bench_*.cpp; do benches+=("$(basename "$source" .cpp)"); done
if ((paper)); then benches=(bench_stator_solve); fi
if ((busy_only)); then benches=(bench_busy); fi

echo "== hotmesh: Release build of the benchmarks (warnings are errors)"
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DHOTMESH_WERROR=ON >/dev/null
cmake --build build -j "$(nproc)" --target "${benches[@]}" make_ramp2d  # make_ramp2d: refined ramps (linear_solvers)

compiler=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' build/CMakeCache.txt)
flags=$(sed -n 's/^CMAKE_CXX_FLAGS_RELEASE:[A-Z]*=//p' build/CMakeCache.txt)
echo
echo "== machine"
echo "date:     $(date -u '+%Y-%m-%d %H:%M UTC')"
echo "commit:   $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
lscpu | grep -E '^(Model name|CPU\(s\)|Thread\(s\) per core|Core\(s\) per socket|L1d|L2|L3)' | sed 's/  */ /g'
free -g | sed -n '1,2p'
echo "compiler: $("$compiler" --version | head -n 1); Release flags: $flags -fopenmp"
load() { echo "load:     $(uptime | sed 's/.*load average: //') (1, 5, 15 min) on $(nproc) cores"; }
load
busy=$(awk -v cores="$(nproc)" '{ print ($1 > 0.5 * cores) ? 1 : 0 }' /proc/loadavg)
if ((busy)); then echo "warning: the machine is busy; the numbers below will be low and noisy" >&2; fi

args_for() {
  if ((quick)); then
    case "$1" in
      bench_operator) echo "--hex 20 --quad 250 --triad-mib 128 --pcg 16" ;;
      bench_ramp) echo "--runs 1" ;;
      bench_projection) echo "20000" ;;
      bench_bspline) echo "--quick" ;;
      bench_renumbering) echo "--quick" ;;
      bench_stator_solve) echo "5000" ;;
      bench_checkpoint) echo "--cells 100000 --runs 1" ;;
      bench_mesh_formats) echo "200000 1" ;;
      bench_busy) echo "--quick" ;;
    esac
  fi
}

# The linear solvers: the 2D samples, three runs each, then the stator-well sample (20 000 hex
# cells) once, then the sliding ramp refined 2 times (9 120 cells: amg, direct and icc) and 4
# times (36 480 cells: direct and icc; amg needed more than 6 minutes for the first 5 of its 16
# increments there), once: where `linear: auto` goes from icc to amg (kIccCells).
linear_solvers() {
  if ((quick)); then
    build/bench/bench_linear_solvers --runs 1
    return
  fi
  build/bench/bench_linear_solvers --runs 3
  echo
  build/bench/bench_linear_solvers --runs 1 samples/stator_well/case_small.yaml
  for refine in 2 4; do
    local folder="build/bench-ramp2d-x$refine"
    build/samples/ramp2d/make_ramp2d --refine "$refine" "$folder" >/dev/null
    cp samples/ramp2d/ramp2d-sliding.yaml "$folder/"
    echo
    build/bench/bench_linear_solvers --runs 1 --linear "$( ((refine < 4)) && echo amg,direct,icc || echo direct,icc)" \
      --forcing fixed "$folder/ramp2d-sliding.yaml"
  done
}

if ((paper)); then
  echo
  echo "== bench_stator_solve 2700000 --forcing eisenstat-walker --ranks 2"
  PETSC_OPTIONS="-matptap_via allatonce -hotmesh_pc_gamg_agg_nsmooths 0" \
    build/bench/bench_stator_solve 2700000 --forcing eisenstat-walker --ranks 2
  echo
  load
  exit 0
fi

for bench in "${benches[@]}"; do
  echo
  echo "== $bench $(args_for "$bench")"
  if [[ "$bench" == bench_linear_solvers ]]; then
    linear_solvers
  else
    # shellcheck disable=SC2046  # the arguments are meant to split
    "build/bench/$bench" $(args_for "$bench")
  fi
  echo
  load
done
