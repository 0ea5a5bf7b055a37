// hotmesh io: OpenFOAM polyMesh folders (points, faces, owner, neighbour, boundary), ASCII or
// binary, each file plain or gzipped. Cells are hexahedra, prisms, pyramids or tetrahedra
// (hexahedra only in 2D cases); patches come from `boundary`.
// One-cell-thick 2D cases (`empty` or `wedge` front and back) are read as 2D quad meshes and
// written back one cell thick. The write-back (MeshWriteBack) writes the moved points in the
// input's format beside the other polyMesh files copied unchanged. docs/openfoam.md is the
// user's reference.
#pragma once

#include <filesystem>
#include <memory>
#include <span>
#include <string_view>

#include "hotmesh/io/mesh_files.hpp"
#include "hotmesh/mesh/mesh.hpp"

namespace hotmesh::io {

/// The polyMesh folder `path` names: `path` itself if it holds a points file, else
/// `path`/constant/polyMesh if that is a folder (a case folder). Throws hotmesh::InputError
/// if neither.
std::filesystem::path foam_mesh_folder(const std::filesystem::path& path);

/// The folder `--foam-time T` writes the moved points into: <case>/T/polyMesh, the case
/// being the folder holding constant/polyMesh that `mesh_path` names. Throws
/// hotmesh::InputError if T is not a time name (a non-negative number: `constant` and paths
/// are refused) or the mesh is not a case's constant/polyMesh.
std::filesystem::path foam_time_folder(const std::filesystem::path& mesh_path, std::string_view time);

/// True if `path` is a folder (read as an OpenFOAM mesh) or is named polyMesh.
bool is_foam_path(const std::filesystem::path& path);

struct FoamWriteOptions {
  bool binary = false;  ///< binary points, faces (faceCompactList), owner and neighbour
};

/// The polyMesh folder write_foam writes for `path`: `path` if it is named polyMesh, else
/// `path`/constant/polyMesh (a case folder; mesh_format() takes only an existing folder so).
std::filesystem::path foam_output_folder(const std::filesystem::path& path);

/// Writes a new polyMesh (points, faces, owner, neighbour, boundary) of the 3D mesh `m`
/// (hexahedra, prisms, pyramids, tetrahedra: their faces triangles and quads) with its nodes at `points` into foam_output_folder(path). Points and cells keep the mesh's
/// order; internal faces come in OpenFOAM's upper-triangular order, then each patch's faces
/// (outward), then the boundary faces in no patch as the wall patch `defaultFaces`. A patch is
/// of type `patch` if its name starts or ends with inlet, outlet, inflow or outflow or starts
/// with per_ or periodic, else `wall`. Throws hotmesh::InputError naming `path` for 2D meshes
/// and patch faces that are not boundary faces.
void write_foam(const std::filesystem::path& path, const mesh::Mesh& m, std::span<const geometry::Vec3> points,
                const FoamWriteOptions& options = {});

struct FoamMesh {
  mesh::Mesh mesh;  ///< not yet validated (see read_mesh in mesh_files.hpp)
  std::shared_ptr<const MeshWriteBack> write_back;
  mesh::Extrusion layer;  ///< a 2D case's back and front planes (empty or wedge)
};

/// Reads the polyMesh of `path` (a polyMesh folder or a case folder).
///
/// - 3D: every cell must be a hexahedron (6 quads), prism (2 triangles, 3 quads), pyramid
///   (1 quad, 4 triangles) or tetrahedron (4 triangles), each edge shared by two of its faces;
///   they become hex8, wedge6, pyramid5 and tet4 in Gmsh's node order with positive volume.
///   Points keep OpenFOAM's order, cells are numbered as OpenFOAM's. Patches with faces
///   become patches (tri3 / quad4, outward), in the order of `boundary`; patches without
///   faces are left out.
/// - 2D: a mesh with faces on `empty` patches (front and back planes normal to x, y or z) or
///   on two `wedge` patches is one cell thick: the result is the mesh of the back plane
///   (the lower coordinate for `empty`, the first wedge patch for `wedge`) in the x-y plane:
///   empty normal to z: (x, y); normal to x: (y, z); normal to y: (z, x); wedge: (axial
///   coordinate, radius) about the line where the wedge planes meet. Its node ids are the
///   OpenFOAM point labels + 1. The empty/wedge patches are dropped, the others become line2
///   patches. The cells of a 2D case must stand on the back plane, each back point joined by
///   one edge to a front point: hexahedra and prisms (quads and triangles in 2D), and in a
///   wedge case the cells collapsed on the axis (their points there on both planes), whose
///   edges on the axis become the patch named as the case's empty patch without faces, or
///   "axis".
/// Throws hotmesh::InputError naming the file and line (or byte offset) for every problem.
FoamMesh read_foam(const std::filesystem::path& path);

}  // namespace hotmesh::io
