// hotmesh io tests: the message a mesh file (or OpenFOAM folder) is refused with.
#pragma once

#include <filesystem>
#include <string>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/mesh_files.hpp"

namespace hotmesh::io::test_io {

/// What read_mesh(path) throws as hotmesh::InputError, or "no error" when it reads the mesh.
inline std::string read_error(const std::filesystem::path& path) {
  try {
    read_mesh(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace hotmesh::io::test_io
