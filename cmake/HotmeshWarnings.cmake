# Warnings for hotmesh's own targets (never for third-party headers, which are SYSTEM includes).
add_library(hotmesh_warnings INTERFACE)
target_compile_options(hotmesh_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast -Wcast-align
  -Wunused -Woverloaded-virtual -Wconversion -Wsign-conversion -Wnull-dereference
  -Wdouble-promotion -Wformat=2 -Wimplicit-fallthrough
  # Options structs with defaults are filled with designated initializers ({.binary = true}),
  # which GCC 12 reports as missing initializers.
  -Wno-missing-field-initializers)
if(HOTMESH_WERROR)
  target_compile_options(hotmesh_warnings INTERFACE -Werror)
endif()
# GCC's -Wmaybe-uninitialized is not reliable under the sanitizers' instrumentation (its
# manual says so): with -fsanitize=address,undefined GCC 12 reports it inside std::regex and
# std::function of the standard library. The Release build keeps the warning.
if(HOTMESH_SANITIZE AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  target_compile_options(hotmesh_warnings INTERFACE -Wno-maybe-uninitialized)
endif()

# hotmesh_module(<name> SOURCES ... [PUBLIC_LIBS ...] [PRIVATE_LIBS ...])
# One library per module, public headers in <module>/include/hotmesh/<module>/.
function(hotmesh_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_LIBS;PRIVATE_LIBS" ${ARGN})
  add_library(hotmesh_${name} ${ARG_SOURCES})
  add_library(hotmesh::${name} ALIAS hotmesh_${name})
  target_include_directories(hotmesh_${name}
    PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include
    PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(hotmesh_${name} PUBLIC ${ARG_PUBLIC_LIBS}
                                        PRIVATE hotmesh_warnings ${ARG_PRIVATE_LIBS})
endfunction()
