# Every dependency is a Debian bookworm package installed by scripts/install-deps.sh.
find_package(OpenCASCADE REQUIRED CONFIG)  # its version file accepts only exact versions
if(OpenCASCADE_VERSION VERSION_LESS 7.6 OR OpenCASCADE_VERSION VERSION_GREATER_EQUAL 7.7)
  message(FATAL_ERROR "hotmesh needs OpenCASCADE 7.6.x, found ${OpenCASCADE_VERSION}")
endif()
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
# CGAL and Boost: header-only uses (CGAL's k-d tree in deform/src/support/nearest_point.cpp, with a Boost iterator).
find_package(CGAL 5.5 REQUIRED CONFIG)
find_package(Boost 1.74 REQUIRED)
find_package(OpenMP REQUIRED COMPONENTS CXX)
find_package(yaml-cpp 0.7 REQUIRED CONFIG)
find_package(CLI11 2.1 REQUIRED CONFIG)
find_package(fmt 9 REQUIRED CONFIG)
find_package(spdlog 1.10 REQUIRED CONFIG)
find_package(nlohmann_json 3.11 REQUIRED CONFIG)
find_package(PkgConfig REQUIRED)
pkg_check_modules(Cairo REQUIRED IMPORTED_TARGET cairo>=1.16)
find_package(ZLIB REQUIRED)  # gzipped OpenFOAM mesh files (points.gz, ...)
# PETSc with Open MPI for the `amg` linear solver (Debian's petsc-dev 3.18). Its PETSc.pc lies
# under the alternative /usr/lib/petsc; its Cflags force _FORTIFY_SOURCE (a warning without
# optimisation), so only the include directory and libraries are taken from it.
set(MPI_CXX_SKIP_MPICXX ON)  # the C API only, not Open MPI's deprecated C++ bindings
find_package(MPI 3.0 REQUIRED COMPONENTS CXX)
if(EXISTS /usr/lib/petsc/lib/pkgconfig)
  set(ENV{PKG_CONFIG_PATH} "/usr/lib/petsc/lib/pkgconfig:$ENV{PKG_CONFIG_PATH}")
endif()
pkg_check_modules(PETSC REQUIRED PETSc>=3.18)
add_library(hotmesh_petsc INTERFACE)
target_include_directories(hotmesh_petsc SYSTEM INTERFACE ${PETSC_INCLUDE_DIRS})
target_link_libraries(hotmesh_petsc INTERFACE ${PETSC_LINK_LIBRARIES} MPI::MPI_CXX)

if(HOTMESH_TESTS)
  find_package(GTest 1.12 REQUIRED CONFIG)
endif()

# OpenCASCADE: its config names Draw toolkits Debian does not ship and forces -std=c++0x through
# OpenCASCADE_CXX_FLAGS, so we link toolkits by name and add the include directory ourselves.
# Only translation units that need OpenCASCADE headers see them (geometry's src/).
add_library(hotmesh_occt INTERFACE)
target_include_directories(hotmesh_occt SYSTEM INTERFACE ${OpenCASCADE_INCLUDE_DIR})
target_link_libraries(hotmesh_occt INTERFACE
  TKernel TKMath TKG2d TKG3d TKGeomBase TKGeomAlgo TKBRep TKTopAlgo TKPrim TKBO TKShHealing
  TKXSBase TKSTEP TKSTEPBase TKSTEPAttr TKSTEP209 TKIGES)
target_link_directories(hotmesh_occt INTERFACE ${OpenCASCADE_LIBRARY_DIR})
# As OpenCASCADE itself is built on Linux: OCC_CATCH_SIGNALS turns a signal inside its code
# into a Standard_Failure (geometry/src/cad/occt_session.hpp).
target_compile_definitions(hotmesh_occt INTERFACE OCC_CONVERT_SIGNALS)

# HTTP for `hotmesh serve`: cpp-httplib (Debian builds it as a library; its pkg-config flags
# carry the feature macros the library was built with, which its header must see too).
pkg_check_modules(HTTPLIB REQUIRED IMPORTED_TARGET cpp-httplib>=0.11)
add_library(hotmesh_httplib INTERFACE)
target_link_libraries(hotmesh_httplib INTERFACE PkgConfig::HTTPLIB)
