// hotmesh io: Gmsh .msh files. Reads formats 2.2 and 4.1, ASCII and binary; writes 4.1.
// Physical groups of (d-1)-dimensional elements become patches (named by $PhysicalNames),
// physical groups of d-dimensional elements become cell groups; d is the highest element
// dimension in the file (2 or 3). Lower-dimensional elements (points, edges of a 3D mesh)
// are skipped. Node and element tags are kept as Mesh::node_ids / Mesh::cell_ids.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string_view>

#include "hotmesh/deform/mesh.hpp"

namespace hotmesh::io {

/// Parses the content of a .msh file. `source` names it in messages. Does not validate the
/// mesh (see read_mesh in mesh_files.hpp). Throws hotmesh::InputError naming the source, the
/// line (ASCII) or byte offset (binary) and what is wrong.
deform::Mesh parse_gmsh(std::string_view content, std::string_view source);

/// Reads a .msh file (parse_gmsh on its content).
deform::Mesh read_gmsh(const std::filesystem::path& path);

struct GmshWriteOptions {
  bool binary = false;
};

/// Writes format 4.1, keeping node order, cell order, node and cell ids, patch names and
/// tags, and cell groups, so that parse_gmsh gives back an equal mesh.
void write_gmsh(std::ostream& out, const deform::Mesh& mesh, const GmshWriteOptions& options = {});
/// Writes a .msh file atomically.
void write_gmsh(const std::filesystem::path& path, const deform::Mesh& mesh,
                const GmshWriteOptions& options = {});

}  // namespace hotmesh::io
