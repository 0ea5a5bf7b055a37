// hotmesh fuzz: Gmsh .msh files (formats 2.2 and 4.1, ASCII and binary) as `hotmesh deform`,
// `info` and `convert` read them: parse_gmsh, then the validation read_mesh does.
#include "fuzz_support.hpp"
#include "hotmesh/mesh/validate.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/gmsh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constexpr std::string_view kSource = "fuzz.msh";
  hotmesh::mesh::Mesh mesh;
  try {
    mesh = hotmesh::io::parse_gmsh(hotmesh::fuzz::as_text(data, size), kSource);
  } catch (const hotmesh::InputError& e) {
    hotmesh::fuzz::require_named(e.what(), kSource);
    return 0;
  }
  try {
    hotmesh::mesh::validate_mesh(mesh);  // its messages are about the mesh; read_mesh adds the file
  } catch (const hotmesh::InputError&) {
  }
  return 0;
}
