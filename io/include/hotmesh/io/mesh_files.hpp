// hotmesh io: mesh files by extension, read and validated in one step.
//   .msh  Gmsh 2.2 / 4.1 (read), 4.1 (write)
//   .vtu  VTK XML unstructured grid (write only: for ParaView)
//   .cgns CGNS, HDF5 or ADF (also .hdf, .adf): read, written back (deformed.cgns), and
//         written new by convert (docs/cgns.md)
//   a folder (or a path named polyMesh): an OpenFOAM polyMesh folder or case (read, written
//         back, and written new from a 3D hex mesh: foam.hpp, docs/openfoam.md)
// A mesh read from another solver's format keeps what it needs to be written back in that
// format (MeshWriteBack), with only the coordinates of its nodes changed.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hotmesh/mesh/mesh.hpp"
#include "hotmesh/mesh/solver_quality.hpp"
#include "hotmesh/mesh/validate.hpp"
#include "hotmesh/io/vtu.hpp"

namespace hotmesh::io {

enum class MeshFormat { gmsh, vtu, cgns, foam };

/// The format a path names by its extension (foam for a folder or a path named polyMesh).
/// Throws hotmesh::InputError for others.
MeshFormat mesh_format(const std::filesystem::path& path);

/// How a run writes its moved mesh back in the format the mesh came from, beside
/// deformed.msh: everything of the input kept, only the nodes' coordinates replaced.
struct WriteBackOptions {
  /// OpenFOAM: also write the moved points into the case's time folder <case>/<foam_time>/polyMesh.
  std::optional<std::string> foam_time;
};

class MeshWriteBack {
 public:
  virtual ~MeshWriteBack() = default;
  /// The files and folders write() creates in an output folder (to check none is an input).
  virtual std::vector<std::string> output_names() const = 0;
  /// Writes the mesh with its nodes at `points` (one per node of the mesh read) into `folder`,
  /// each file atomically; returns the paths written.
  virtual std::vector<std::filesystem::path> write(const std::filesystem::path& folder,
                                                   std::span<const geometry::Vec3> points,
                                                   const WriteBackOptions& options) const = 0;
};

struct LoadedMesh {
  mesh::Mesh mesh;
  mesh::ValidationReport validation;
  std::shared_ptr<const MeshWriteBack> write_back;  ///< null for Gmsh files (deformed.msh is theirs)
  /// The layer of cells a 2D mesh stands for in its flow solver: an OpenFOAM case's empty or
  /// wedge planes, else a slab (mesh::solver_quality).
  mesh::Extrusion layer;
};

/// The files a mesh input is made of, for fingerprints: the file itself, or the files of a
/// mesh folder.
std::vector<std::filesystem::path> mesh_input_files(const std::filesystem::path& path);

/// Reads and validates a mesh; every error names the file.
LoadedMesh read_mesh(const std::filesystem::path& path);

/// Writes `mesh` with its nodes at `points` in the format of the extension; VTU files get
/// `fields` (plus nothing else), Gmsh files ignore them.
void write_mesh(const std::filesystem::path& path, const mesh::Mesh& mesh, std::span<const geometry::Vec3> points,
                const VtuFields& fields = {});

}  // namespace hotmesh::io
