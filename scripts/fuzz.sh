#!/usr/bin/env bash
# hotmesh: fuzz every reader of user input (docs/fuzzing.md).
#   1. builds the libFuzzer targets it runs (fuzz/: clang, ASan + UBSan) and hotmesh in build-fuzz/,
#   2. gathers each target's seeds in build-fuzz/fuzz/seeds/<target>/: the samples, the test
#      data, fuzz/corpus/<target>/, a restart and a checkpoint file of a short run of the
#      ramp2d sample, the coupled_disc sample's deck solved by ccx (ASCII and binary .frd),
#      and the small decks and results of Debian's CalculiX tests (calculix-ccx-test), the
#      stator well's sector as a binary gzipped polyMesh and the polyMesh folders of Debian's
#      OpenFOAM tutorials (openfoam-examples: some as shipped, two made by blockMesh), the
#      tests' small CGNS files and two of its gmsh meshes as hotmesh writes them as CGNS, in
#      HDF5 and ADF,
#   3. runs each target for SECONDS (default 60), one after the other (-j N: N at a time),
#      growing its corpus in build-fuzz/fuzz/corpus/<target>/ (kept between runs), and prints
#      the executions each reached.
# Exits non-zero if a target crashed; the input that crashed it is kept in
# build-fuzz/fuzz/findings/<target>/ (crash-*, leak-*, timeout-*, oom-*), and
# `build-fuzz/fuzz/fuzz_<target> <that file>` runs it again.
# Usage: scripts/fuzz.sh [-j N] [--hotmesh EXE] [--build DIR] [SECONDS] [TARGET...]
#                  (all targets by default)
#   --hotmesh EXE  makes the restart and checkpoint seeds with this hotmesh (a Release build is
#                  much faster than the sanitizer build that is made otherwise)
#   --build DIR    builds the targets in DIR, a build folder already configured with clang and
#                  -DHOTMESH_FUZZ=ON (scripts/test.sh's sanitizer build, which has the tests
#                  too), instead of configuring build-fuzz/
set -euo pipefail

# The whole script is one function, read before it runs, and the line that calls it also
# exits: editing this file while a long run goes on does not change the run.
main() {
  cd "$(dirname "$0")/.."

  all_targets=(gmsh deflection_csv case_yaml restart checkpoint frd inp foam cgns serve_json serve_upload step iges)
  seconds=60
  parallel=1
  seed_hotmesh=""
  targets=()
  build=build-fuzz
  configure=1
  usage="usage: scripts/fuzz.sh [-j N] [--hotmesh EXE] [--build DIR] [SECONDS] [TARGET...]   targets: ${all_targets[*]}"
  while (($#)); do
    case "$1" in
      -j) [[ ${2:-} =~ ^[1-9][0-9]*$ ]] || { echo "$usage" >&2; exit 2; }; parallel=$2; shift ;;
      --hotmesh) [[ -x ${2:-} ]] || { echo "fuzz.sh: --hotmesh needs an executable, got '${2:-}'" >&2; exit 2; }
                 seed_hotmesh=$(realpath "$2"); shift ;;
      --build) grep -qs '^HOTMESH_FUZZ:BOOL=ON' "${2:-}/CMakeCache.txt" ||
                 { echo "fuzz.sh: --build needs a build folder configured with -DHOTMESH_FUZZ=ON, got '${2:-}'" >&2; exit 2; }
               build=$2; configure=0; shift ;;
      *) if [[ "$1" =~ ^[0-9]+$ ]]; then
           seconds=$1
         elif [[ " ${all_targets[*]} " == *" $1 "* ]]; then
           targets+=("$1")
         else
           echo "$usage" >&2
           exit 2
         fi ;;
    esac
    shift
  done
  ((${#targets[@]})) || targets=("${all_targets[@]}")

  out=$build/fuzz
  jobs=$(nproc)
  ccx_tests=/usr/share/doc/calculix-ccx-test/examples/test
  foam_tutorials=/usr/share/doc/openfoam-examples/examples
  if ! command -v clang++ >/dev/null || ! command -v gmsh >/dev/null || ! command -v ccx >/dev/null ||
     [[ ! -d $ccx_tests ]]; then
    echo "hotmesh: the fuzz targets need clang++, gmsh, ccx and CalculiX's tests (calculix-ccx-test):" \
         "run scripts/install-deps.sh" >&2
    exit 1
  fi

  echo "== hotmesh: fuzz targets (clang, libFuzzer, ASan + UBSan) in $build/"
  if ((configure)); then
    cmake -S . -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug \
          -DCMAKE_CXX_FLAGS_DEBUG="-g1 -O2" -DCGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE=ON -DHOTMESH_WERROR=ON \
          -DHOTMESH_FUZZ=ON -DHOTMESH_TESTS=OFF -DHOTMESH_BENCH=OFF >/dev/null
  fi
  # Only the targets that run (fuzz.sh 600 inp builds fuzz_inp alone).
  fuzzers=("${targets[@]/#/fuzz_}")
  if [[ -n $seed_hotmesh ]]; then
    cmake --build "$build" -j "$jobs" --target "${fuzzers[@]}"
    hotmesh=$seed_hotmesh
  else
    cmake --build "$build" -j "$jobs" --target "${fuzzers[@]}" hotmesh
    hotmesh=$(pwd)/$build/app/hotmesh
  fi

  # Sanitizer settings of every run: third-party caches that are never freed are not leaks
  # (tests/lsan.supp); a finding stops the target.
  export ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1
  export LSAN_OPTIONS=suppressions=$(pwd)/tests/lsan.supp:print_suppressions=0
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive

  # A restart file and a checkpoint of the ramp2d sample, made again whenever hotmesh or the
  # sample changed. The checkpoint, of the sample's own case killed with SIGKILL right after
  # its first checkpoint by the tests' fault library (tests/support/fault_library.cpp, built
  # here: this build has no tests), names the case's files and their hashes (so it belongs to
  # this checkout, as fuzz_checkpoint checks); the restart file comes from a whole run of two
  # increments on the sample's mesh and patches, with a small bump for the bottom wall to slide
  # over (the sample's ramp takes a minute under the sanitizers).
  state_runs=$out/state-runs
  ramp2d=$(pwd)/samples/ramp2d
  newest_input=$(ls -t "$hotmesh" "$ramp2d"/ramp2d-sliding.yaml "$ramp2d"/ramp2d.msh "$ramp2d"/ramp.csv |
                 head -1)
  if [[ ! -f $state_runs/checkpoint/checkpoint.hmc || $newest_input -nt $state_runs/checkpoint/checkpoint.hmc ]]; then
    echo "== hotmesh: short runs of samples/ramp2d for the restart and checkpoint seeds"
    rm -rf "$state_runs"
    mkdir -p "$state_runs"
    printf 'x,y,dx,dy\n0,0,0,0\n1,0,0,0.001\n2,0,0,0\n' > "$state_runs/bump.csv"
    sed -e "s|^mesh: .*|mesh: $ramp2d/ramp2d.msh|" -e "s|file: ramp.csv|file: bump.csv|" \
        -e "s|increments: 16|increments: 2|" \
        -e '/^pictures:/,$d' "$ramp2d/ramp2d-sliding.yaml" > "$state_runs/bump.yaml"
    ASAN_OPTIONS=detect_leaks=0 "$hotmesh" -q deform "$state_runs/bump.yaml" -o "$state_runs/restart"
    clang++ -std=c++20 -O2 -shared -fPIC tests/support/fault_library.cpp -o "$state_runs/libhotmesh_faults.so" -ldl
    { ASAN_OPTIONS=detect_leaks=0 LD_PRELOAD="$state_runs/libhotmesh_faults.so" HOTMESH_TEST_KILL_AFTER_CHECKPOINT=1 \
        "$hotmesh" -q deform "$ramp2d/ramp2d-sliding.yaml" -o "$state_runs/checkpoint" || true; } 2>/dev/null
    [[ -f $state_runs/checkpoint/checkpoint.hmc ]] || { echo "hotmesh: no checkpoint.hmc was written" >&2; exit 1; }
  fi

  # Seeds: files below 1 MB (larger ones make each execution slow without reaching more code).
  small() { find "$@" -maxdepth 1 -type f -size -1024k 2>/dev/null | sort; }
  # CAD files of the tests and the shared real-world ones, each name once.
  cad_files() { small tests/data/cad ../shared/data/cad-real | grep -iE "\\.($1)\$" | awk -F/ '!seen[$NF]++'; }
  seeds=$out/seeds
  rm -rf "$seeds"
  for t in "${all_targets[@]}"; do
    mkdir -p "$seeds/$t"
    [[ -d fuzz/corpus/$t ]] && cp fuzz/corpus/"$t"/* "$seeds/$t/"
  done
  cp $(small samples/* | grep '\.msh$') "$seeds/gmsh/"
  for geo in tests/data/gmsh/*.geo; do  # the four flavours gmsh writes: 2.2 and 4.1, ASCII and binary
    name=$(basename "$geo" .geo)
    dimension=3; [[ $name == quad_* ]] && dimension=2
    for format in msh22 msh41; do
      gmsh -$dimension -nt 1 "$geo" -format $format -o "$seeds/gmsh/$name-$format.msh" >/dev/null
      gmsh -$dimension -nt 1 "$geo" -format $format -bin -o "$seeds/gmsh/$name-$format-bin.msh" >/dev/null
    done
  done
  cp $(small samples/* | grep '\.csv$') "$seeds/deflection_csv/"
  cp $(small samples/* | grep '\.yaml$') "$seeds/case_yaml/"
  # CalculiX: the coupled_disc deck as one input of fuzz_inp (its *INCLUDE is the target's
  # 1.inp, after a `**>` line), solved by ccx into an ASCII and a binary .frd (its surfaces are
  # the ones fuzz_frd reads); the test files of hotmesh and of Debian's calculix-ccx-test below
  # 8 KB (decks) and 16 KB (results).
  disc=samples/coupled_disc
  { sed 's/INPUT=disc_mesh.inp/INPUT=1.inp/' "$disc/disc_1.inp"; echo '**> 1.inp: disc_mesh.inp'
    cat "$disc/disc_mesh.inp"; } > "$seeds/inp/coupled_disc.inp"
  ccx_runs=$out/ccx-runs
  rm -rf "$ccx_runs"
  mkdir -p "$ccx_runs"
  cp "$disc/disc_1.inp" "$disc/disc_mesh.inp" "$ccx_runs/"
  sed 's/^\*NODE FILE/*NODE OUTPUT/' "$disc/disc_1.inp" > "$ccx_runs/disc_1_binary.inp"
  for job in disc_1 disc_1_binary; do
    (cd "$ccx_runs" && ccx -i "$job" > "$job.log" 2>&1) || { echo "hotmesh: ccx failed on $ccx_runs/$job.inp" >&2; exit 1; }
    cp "$ccx_runs/$job.frd" "$seeds/frd/"
  done
  cp tests/data/calculix/*.inp "$seeds/inp/"
  cp tests/data/calculix/*.frd "$seeds/frd/"
  unpacked() {  # unpacked <pattern> <folder> <bytes>: the files of calculix-ccx-test smaller than <bytes>, unzipped
    local file
    for file in "$ccx_tests"/$1; do
      zcat -f "$file" > "$2.tmp"
      if (($(stat -c %s "$2.tmp") < $3)); then mv "$2.tmp" "$2/ccx-$(basename "${file%.gz}")"; fi
    done
    rm -f "$2.tmp"
  }
  unpacked '*.inp*' "$seeds/inp" 8192
  unpacked '*.frd.ref*' "$seeds/frd" 16384
  # OpenFOAM: one input per polyMesh folder, each file after a line `//> NAME` (fuzz_foam.cpp).
  # fuzz/corpus/foam/ (the block of two cubes in every file form, a cell of each type, a 2D
  # case, uniform lists); the stator well's sector (samples/stator_well, case_small_foam.yaml's
  # mesh) as make_stator_well --engine-formats writes it (hotmesh convert of its .msh: the same
  # polyMesh writer), binary and gzipped (720 KB); the polyMesh folders of Debian's OpenFOAM
  # tutorials (openfoam-examples) below 1 MB uncompressed, as shipped (gzipped, in OpenFOAM
  # 1.4's format), and blockMesh's meshes of two tutorials: the cavity (2D, empty) and the
  # moving cone (2D, wedge).
  foam_input() {  # foam_input <polyMesh folder> <input file>
    local name file
    for name in points faces owner neighbour boundary; do
      for file in "$1/$name" "$1/$name.gz"; do
        [[ -f $file ]] || continue
        printf '//> %s\n' "$(basename "$file")"
        cat "$file"
        echo
      done
    done > "$2"
  }
  foam_runs=$out/foam-runs
  if [[ ! -f $foam_runs/done || $hotmesh -nt $foam_runs/done ]]; then
    echo "== hotmesh: the stator well's polyMesh and blockMesh's meshes of two tutorials for the foam seeds"
    rm -rf "$foam_runs"
    mkdir -p "$foam_runs"
    ASAN_OPTIONS=detect_leaks=0 "$hotmesh" -q convert samples/stator_well/stator_well.msh \
      "$foam_runs/stator_well/polyMesh" --binary
    gzip -9 "$foam_runs"/stator_well/polyMesh/*
    if [[ -d $foam_tutorials ]] && command -v blockMesh >/dev/null; then
      for tutorial in incompressible/icoFoam/cavity/cavity incompressible/pimpleFoam/laminar/movingCone; do
        cp -r "$foam_tutorials/$tutorial" "$foam_runs/$(basename "$tutorial")"
        WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam} blockMesh -case "$foam_runs/$(basename "$tutorial")" \
          > "$foam_runs/$(basename "$tutorial").log" 2>&1 ||
          { echo "hotmesh: blockMesh failed on $tutorial (see $foam_runs/)" >&2; exit 1; }
      done
    fi
    touch "$foam_runs/done"
  fi
  foam_input "$foam_runs/stator_well/polyMesh" "$seeds/foam/stator_well"
  for mesh in "$foam_runs"/*/constant/polyMesh; do
    [[ -d $mesh ]] && foam_input "$mesh" "$seeds/foam/blockMesh-$(basename "$(dirname "$(dirname "$mesh")")")"
  done
  if [[ -d $foam_tutorials ]]; then
    for mesh in $(find "$foam_tutorials" -type d -name polyMesh | sort); do
      [[ -f $mesh/points || -f $mesh/points.gz ]] || continue
      (($(zcat -f "$mesh"/* | wc -c) < 1048576)) || continue  # below 1 MB uncompressed
      foam_input "$mesh" "$seeds/foam/tutorial-$(echo "${mesh#"$foam_tutorials"/}" | tr / -)"
    done
  fi
  # CGNS: the tests' small files (fuzz/cgns_seeds, built with fuzz_cgns: unstructured 2D and
  # 3D with MIXED sections, structured 2D and 3D in two zones with 1-to-1, periodic and
  # abutting connections), two meshes as `hotmesh convert` writes them (the hybrid plate and
  # box of tests/data/gmsh, made above: MIXED cell sections, a MIXED face section; the
  # samples' meshes, 150 KB and more as CGNS, made each execution ten times slower), and each
  # again in ADF (hdf2adf, cgns-convert), the CGNS library's other file format.
  if [[ -x $build/fuzz/cgns_seeds ]]; then
    ASAN_OPTIONS=detect_leaks=0 "$build/fuzz/cgns_seeds" "$seeds/cgns"
    for name in hybrid_plate hybrid_box; do
      ASAN_OPTIONS=detect_leaks=0 "$hotmesh" -q convert "$seeds/gmsh/$name-msh41.msh" "$seeds/cgns/$name.cgns"
    done
    if command -v hdf2adf >/dev/null; then
      for file in "$seeds"/cgns/*.cgns; do
        hdf2adf "$file" "${file%.cgns}-adf.cgns" >/dev/null
      done
    fi
  fi
  cp "$state_runs/restart/restart.hmr" "$seeds/restart/"
  cp "$state_runs/checkpoint/checkpoint.hmc" "$seeds/checkpoint/"
  cp $(cad_files "step|stp") "$seeds/step/"
  cp $(cad_files "iges|igs") "$seeds/iges/"
  for file in $(cad_files "step|stp|iges|igs"); do
    { printf '%s\nmm\n' "$(basename "$file")"; cat "$file"; } > "$seeds/serve_upload/$(basename "$file")"
  done

  # The runs, `parallel` targets at a time. Limits: an input that runs a minute is a hang, one
  # allocation above 512 MB (from inputs under 1 MB) a finding, as is a process above 4 GB.
  # The targets that read STEP and IGES files run in a child process that libFuzzer replaces
  # now and then (-fork=1), where a hang is kept in findings/ and counted but does not stop
  # the run: OpenCASCADE's readers are not hotmesh's to fix, and its STEP reader did spin on
  # damaged files (those hotmesh now refuses first, docs/fuzzing.md); a count above zero in the
  # summary is a finding to look at.
  # Each run writes its line of the summary to logs/<target>.summary, and logs/<target>.failed
  # if the target crashed.
  run_target() {
    local t=$1
    local log=$out/logs/$t.log
    local options=(-max_total_time="$seconds" -timeout=60 -rss_limit_mb=4096 -malloc_limit_mb=512
                   -print_final_stats=1 -artifact_prefix="$out/findings/$t/")
    [[ -f fuzz/dict/$t.dict ]] && options+=(-dict="fuzz/dict/$t.dict")
    local occt=0 library=0
    [[ " step iges serve_upload " == *" $t "* ]] && occt=1
    [[ $t == cgns ]] && library=1
    ((occt)) && options+=(-fork=1 -ignore_timeouts=1)
    ((library)) && options+=(-fork=1 -ignore_crashes=1)
    local hangs_before findings_before
    hangs_before=$(find "$out/findings/$t" -name 'timeout-*' | wc -l)
    findings_before=$(find "$out/findings/$t" -type f | sort)
    rm -f "$log.alone"
    echo "== hotmesh: fuzz_$t for $seconds s (log: $log)"
    local status=0
    "$out/fuzz_$t" "${options[@]}" "$out/corpus/$t" "$seeds/$t" >"$log" 2>&1 || status=$?
    local coverage hangs="" runs found artifact
    coverage=$(grep -oE 'cov: [0-9]+' "$log" | tail -1 || true)
    if ((occt)); then  # the parent prints "#<executions>: cov: ..." lines, and exits 70 after a hang
      runs=$(grep -oE '^#[0-9]+:' "$log" | tail -1 | tr -d '#:' || true)
      ((status == 70)) && status=0
      found=$(($(find "$out/findings/$t" -name 'timeout-*' | wc -l) - hangs_before))
      ((found > 0)) && hangs="  ($found hang(s) inside OpenCASCADE kept in $out/findings/$t/)"
    elif ((library)); then
      # The CGNS library (3.4, and HDF5 beneath it) faults on some damaged files: a wild read
      # in its ADF reader, an assertion of its table of open ADF files after an earlier damaged
      # file. hotmesh reads every CGNS file in a child process first, where such a fault is an
      # error naming the file (io/src/cgns/cgns_library.hpp); the target reads in its own process,
      # to see hotmesh's code. So the run goes on past a crash (-fork), and each input kept is
      # run again alone: one that fails alone with a report whose stack reaches libcgns or
      # libhdf5 before hotmesh's code (a signal, an assertion, memory asked for inside the
      # library, an overflow of a buffer the library allocated itself) is the library's and is
      # counted; any other failing alone (an overflow of hotmesh's buffer, undefined behaviour
      # in hotmesh) is a finding and fails the run.
      runs=$(grep -oE '^#[0-9]+:' "$log" | tail -1 | tr -d '#:' || true)
      status=0
      local new_findings=() ours=() file report library_faults=0 earlier_state=0
      mapfile -t new_findings < <(comm -13 <(echo "$findings_before") <(find "$out/findings/$t" -type f | sort))
      for file in "${new_findings[@]}"; do
        [[ -n $file ]] || continue
        report=$("$out/fuzz_$t" -timeout=60 -rss_limit_mb=4096 -malloc_limit_mb=512 "$file" 2>&1) && {
          earlier_state=$((earlier_state + 1)); continue; }
        printf '== %s\n%s\n' "$file" "$report" >>"$log.alone"
        if ! grep -q 'runtime error' <<<"$report" && awk '
             /allocated by thread/ { in_allocation = 1; next }
             /^ +#[0-9]+ / {
               if (!in_allocation) {
                 if (!top_seen && $0 ~ /libcgns\.so|libhdf5/) { library = 1; top_seen = 1 }
                 else if (!top_seen && $0 ~ /hotmesh::|LLVMFuzzerTestOneInput/) top_seen = 1
               } else if (!allocation_seen && $0 !~ / in (malloc|calloc|realloc|operator new|__interceptor_)/) {
                 allocation_seen = 1; allocated_by_library = ($0 ~ /libcgns\.so|libhdf5/)
               }
             }
             END { exit !(library && (!in_allocation || allocated_by_library)) }' <<<"$report"; then
          library_faults=$((library_faults + 1))
        else
          ours+=("$file")
        fi
      done
      if ((${#ours[@]})); then
        status=1
        echo "Test unit written to ${ours[*]} (fails alone: $log.alone)" >>"$log"
      elif ((library_faults + earlier_state)); then
        hangs="  ($library_faults fault(s) inside the CGNS library, $earlier_state only after other inputs; kept in $out/findings/$t/)"
      fi
    else
      runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    fi
    if ((status == 0)); then
      printf '%-16s %10s executions  %s%s\n' "$t" "${runs:-?}" "$coverage" "$hangs" > "$out/logs/$t.summary"
    else
      artifact=$(sed -n 's/.*Test unit written to //p' "$log" | tail -1)
      printf '%-16s FAILED (exit %d) after %s executions: %s\n' "$t" "$status" "${runs:-?}" \
             "${artifact:-see $log}" > "$out/logs/$t.summary"
      tail -n 60 "$log" > "$out/logs/$t.failed"
    fi
  }

  mkdir -p "$out/logs"
  # The targets' files, a folder per process (and one in /dev/shm, fuzz_support's
  # memory_folder): a process that crashed or was stopped leaves its own. Only those of processes that ended go, so a second fuzz.sh on the same build (other
  # targets) does not pull the files from under the first one's targets.
  for folder in "$out"/work/*/ /dev/shm/hotmesh-fuzz/*/; do
    [[ -d $folder ]] || continue
    kill -0 "$(basename "$folder")" 2>/dev/null || rm -rf "$folder"
  done
  for t in "${targets[@]}"; do
    mkdir -p "$out/corpus/$t" "$out/findings/$t"
    rm -f "$out/logs/$t.summary" "$out/logs/$t.failed"
  done
  running=0
  for t in "${targets[@]}"; do
    if ((running == parallel)); then
      wait -n || true
      running=$((running - 1))
    fi
    run_target "$t" &
    running=$((running + 1))
  done
  wait || true
  failed=()
  summary=()
  for t in "${targets[@]}"; do
    summary+=("$(cat "$out/logs/$t.summary" 2>/dev/null || echo "$t: no result (see $out/logs/$t.log)")")
    if [[ -f $out/logs/$t.failed || ! -f $out/logs/$t.summary ]]; then
      failed+=("$t")
      cat "$out/logs/$t.failed" 2>/dev/null || true
    fi
  done

  echo "== hotmesh: fuzzing, $seconds s per target"
  printf '%s\n' "${summary[@]}"
  if ((${#failed[@]})); then
    echo "hotmesh: ${#failed[@]} fuzz target(s) crashed: ${failed[*]}; inputs in $out/findings/, run one again with" \
         "$out/fuzz_<target> <file>" >&2
    exit 1
  fi
}

main "$@"; exit
