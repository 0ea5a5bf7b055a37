// hotmesh io: Gmsh .msh files. Reads formats 2.2 and 4.1, ASCII and binary; writes 4.1.
// Physical groups of (d-1)-dimensional elements become patches (named by $PhysicalNames),
// physical groups of d-dimensional elements become cell groups; d is the highest element
// dimension in the file (2 or 3). Lower-dimensional elements (points, edges of a 3D mesh)
// are skipped. Node and element tags are kept as Mesh::node_ids / Mesh::cell_ids.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string_view>

#include "hotmesh/mesh/mesh.hpp"

namespace hotmesh::io {

/// Parses the content of a .msh file. `source` names it in messages. Does not validate the
/// mesh (see read_mesh in mesh_files.hpp). Throws hotmesh::InputError naming the source, the
/// line (ASCII) or byte offset (binary) and what is wrong.
///
/// - Cells are all elements of dimension d, in file order; nodes are in file order. Node_ids
///   and cell_ids always hold the file's tags (for a cell that 2.2 repeats, its first tag).
/// - Patches (ordered by tag) are the physical groups of dimension d-1, cell groups (ordered by
///   tag, cells ascending) those of dimension d; both include groups that $PhysicalNames names
///   but no element uses. Every group used by elements must be named; two patches must not
///   share a name. Elements of dimension d-1 in no group are skipped. Patch::nodes is filled.
/// - An element in several groups (4.1: an entity with several physical tags; 2.2: the same
///   element repeated in consecutive records, one per group, as gmsh writes it) is one cell
///   in each of its groups, or one face in each of its patches.
/// - Supported element types: line2, tri3, quad4, tet4, hex8, prism (wedge6), pyramid5 (Gmsh
///   numbering = hotmesh numbering); points are skipped; anything else is an error.
/// - 4.1 files with $PartitionedEntities are rejected; 2.2 files of partitioned meshes list
///   every element once and are read whole (partition tags ignored). Sections the reader does
///   not need ($Comments, $NodeData, $Periodic, ...) are skipped; CRLF line ends are accepted.
mesh::Mesh parse_gmsh(std::string_view content, std::string_view source);

/// Reads a .msh file (parse_gmsh on its content).
mesh::Mesh read_gmsh(const std::filesystem::path& path);

struct GmshWriteOptions {
  bool binary = false;  ///< 4.1 binary (this machine's byte order, 64-bit size_t) instead of ASCII
};

/// Writes format 4.1, keeping node order, cell order, node and cell ids, patch names and
/// tags, and cell groups, so that parse_gmsh gives back an equal mesh (for a mesh as the reader
/// makes it: ids filled, patches and groups ordered by tag, group cells ascending, patch node
/// sets derived). Empty node_ids / cell_ids are written as 1, 2, 3, ...; patch face tags are
/// numbered after the largest cell id. A patch or group tag that is not positive or repeats an
/// earlier one is replaced by a new number above the largest. Throws std::invalid_argument for
/// a mesh that cannot be stored (references to missing nodes or cells, cells not of the mesh's
/// dimension, a name holding a double quote or line break). Check the stream's state afterwards.
/// gmsh itself (4.8) saves only elements in physical groups: cells in no group are kept by
/// hotmesh's reader but dropped if the file is re-saved by gmsh.
void write_gmsh(std::ostream& out, const mesh::Mesh& mesh, const GmshWriteOptions& options = {});
/// Writes a .msh file atomically (io::AtomicFile): an existing file is replaced only once the
/// new one is complete. Throws hotmesh::InputError if the file cannot be written.
void write_gmsh(const std::filesystem::path& path, const mesh::Mesh& mesh, const GmshWriteOptions& options = {});

}  // namespace hotmesh::io
