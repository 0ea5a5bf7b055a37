// hotmesh io: mesh files by extension, read and validated in one step.
//   .msh  Gmsh 2.2 / 4.1 (read), 4.1 (write)
//   .vtu  VTK XML unstructured grid (write only: for ParaView)
#pragma once

#include <filesystem>
#include <span>

#include "hotmesh/mesh/mesh.hpp"
#include "hotmesh/mesh/validate.hpp"
#include "hotmesh/io/vtu.hpp"

namespace hotmesh::io {

enum class MeshFormat { gmsh, vtu };

/// The format a path names by its extension. Throws hotmesh::InputError for others.
MeshFormat mesh_format(const std::filesystem::path& path);

struct LoadedMesh {
  mesh::Mesh mesh;
  mesh::ValidationReport validation;
};

/// Reads and validates a mesh; every error names the file.
LoadedMesh read_mesh(const std::filesystem::path& path);

/// Writes `mesh` with its nodes at `points` in the format of the extension; VTU files get
/// `fields` (plus nothing else), Gmsh files ignore them.
void write_mesh(const std::filesystem::path& path, const mesh::Mesh& mesh, std::span<const geometry::Vec3> points,
                const VtuFields& fields = {});

}  // namespace hotmesh::io
