# hotmesh tests: `cmake --install` into a fresh prefix in a temporary folder, then a project
# outside hotmesh's build (tests/install/consumer) finds the package, links hotmesh::hotmesh
# and moves the 2D ramp in memory; the installed command moves it from the files, and both
# must write the same deformed.msh, byte for byte.
#   cmake -DBUILD_DIR=<hotmesh build> -DSOURCE_DIR=<hotmesh source> -P install_and_use.cmake
cmake_minimum_required(VERSION 3.25)
string(RANDOM LENGTH 8 tag)
set(work "$ENV{TMPDIR}")
if(NOT work)
  set(work /tmp)
endif()
set(work "${work}/hotmesh-install-${tag}")
file(REMOVE_RECURSE "${work}")

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE code)
  if(NOT code EQUAL 0)
    file(REMOVE_RECURSE "${work}")
    message(FATAL_ERROR "failed (${code}): ${ARGN}")
  endif()
endfunction()

set(prefix "${work}/prefix")
run(${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}")
foreach(installed bin/hotmesh include/hotmesh/hotmesh.hpp include/hotmesh/core/input_error.hpp
                  lib/cmake/hotmesh/hotmeshConfig.cmake)
  if(NOT EXISTS "${prefix}/${installed}")
    message(FATAL_ERROR "cmake --install did not install ${installed}")
  endif()
endforeach()

run(${CMAKE_COMMAND} -S "${SOURCE_DIR}/tests/install/consumer" -B "${work}/build" -G Ninja
    -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${prefix}")
run(${CMAKE_COMMAND} --build "${work}/build")

set(ramp "${SOURCE_DIR}/samples/ramp2d")
set(case_file "${work}/ramp.yaml")  # the sample without pictures: the mesh is what is compared
file(WRITE "${case_file}" "mesh: ${ramp}/ramp2d.msh\nsolver: {increments: 16}\npatches:\n  left: {role: fixed}\n"
     "  right: {role: slip}\n  top: {role: sliding}\n"
     "  bottom: {role: sliding, deflection: {file: ${ramp}/ramp.csv, degree: 1}}\n")
run("${work}/build/move_ramp" "${case_file}" "${ramp}/ramp.csv" bottom "${work}/library-out")
run("${prefix}/bin/hotmesh" deform "${case_file}" -o "${work}/command-out" -q)
file(SHA256 "${work}/library-out/deformed.msh" library)
file(SHA256 "${work}/command-out/deformed.msh" command)
file(REMOVE_RECURSE "${work}")
if(NOT library STREQUAL command)
  message(FATAL_ERROR "the program built on the installed library wrote another deformed.msh than the installed command")
endif()
message(STATUS "the installed package builds a program outside hotmesh that moves the ramp as the command does")
