// hotmesh mesh: cell quality as a finite-volume flow solver sees it, in OpenFOAM's definitions
// (checkMesh; primitiveMeshTools and the face and cell centres of primitiveMesh), so that the
// numbers hotmesh reports are the ones its users' solvers and checkMesh print:
//   face centre and area vector: triangles from each edge to the mean of the face's points,
//     their centroids weighted by their areas; the area vector half the sum of their normals;
//   cell centre and volume: pyramids from each face to the mean of the face centres;
//   non-orthogonality of an internal face: the angle between its area vector and the line
//     joining the two cell centres; checkMesh's average is the angle of the mean cosine;
//   skewness of a face: how far the face centre lies from where that line crosses the face,
//     over the distance from the face centre to the face's edge in that direction (at least
//     0.2 of the line's length); a boundary face is measured against the cell's mirror image;
//   volume ratio: max/min of the two cells of an internal face (checkMesh -allGeometry prints
//     min/max; hotmesh the reciprocal, as ratios are read);
//   aspect ratio: the largest ratio of the cell's summed face areas projected on two of the
//     mesh's Cartesian axes, and in 3D at least (1/6) sum |S| / V^(2/3) (1 for a cube).
// Beside them, the angle between a boundary face's area vector and the line from the cell
// centre to the face centre (the non-orthogonality a solver corrects at a wall).
// A mesh with polyhedra (Mesh::polyhedra) is measured on the file's cells, each polyhedron
// on its own faces, not on its pieces; its values are given to each of its pieces, and the
// per-type summaries leave polyhedra out (they have no element type).
// A 2D mesh stands for one layer of cells between two planes (Extrusion): a slab for a planar
// case, a wedge for an axisymmetric one; its cells are measured as those prisms.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <vector>

#include "hotmesh/mesh/mesh.hpp"

namespace hotmesh::mesh {

/// A plane of a 2D mesh's layer in 3D: the 2D point (x, y) stands at origin + x u + y v.
struct PlaneMap {
  Vec3 origin{};
  Vec3 u{1, 0, 0};
  Vec3 v{0, 1, 0};
  Vec3 at(const Vec3& p) const { return origin + p.x * u + p.y * v; }
};

/// The layer of cells a 2D mesh stands for: each 2D point at back.at(p) and front.at(p). The
/// default is a slab of unit thickness (the measures do not depend on it); an OpenFOAM wedge
/// case gives its two wedge planes.
struct Extrusion {
  PlaneMap back{};
  PlaneMap front{{0, 0, 1}};
};

/// The worst value of a measure and the cell that has it (-1: no cell has the measure).
struct WorstCell {
  double value = 0.0;
  CellId cell = -1;
};

struct SolverQualitySummary {
  std::size_t cells = 0;
  std::size_t internal_faces = 0;
  WorstCell max_non_orthogonality;   ///< degrees, internal faces
  double mean_non_orthogonality = 0; ///< degrees: checkMesh's average, acos of the mean cosine
  std::size_t severely_non_orthogonal_faces = 0;  ///< internal faces above 70 degrees (checkMesh)
  WorstCell max_boundary_non_orthogonality;       ///< degrees, boundary faces (not a 2D layer's planes)
  WorstCell max_skewness;      ///< every face
  WorstCell max_volume_ratio;  ///< internal faces, >= 1
  WorstCell max_aspect_ratio;
};

struct SolverQuality {
  /// Per cell, the worst of its faces: non-orthogonality in degrees of its internal faces (0
  /// without any), skewness of all its faces, volume ratio with each neighbour (1 without any);
  /// and its aspect ratio.
  std::vector<double> non_orthogonality, skewness, volume_ratio, aspect_ratio;
  SolverQualitySummary summary;
  /// The same over the cells of each type (a face counts for the types of both its cells).
  std::map<ElementType, SolverQualitySummary> by_type;
};

/// A face's centre and area vector (OpenFOAM's), its points in order (the area vector by the
/// right-hand rule).
struct FaceGeometry {
  Vec3 centre, area;
};
FaceGeometry face_geometry(std::span<const Vec3> polygon);

/// A cell's centre and volume (OpenFOAM's) from the geometry of its outward faces.
struct CellCentre {
  Vec3 centre;
  double volume = 0.0;
};
CellCentre cell_centre(std::span<const FaceGeometry> faces);

/// A cell as the solver sees it.
struct CellMeasures {
  Vec3 centre;
  double volume = 0.0;
  double aspect_ratio = 1.0;
  double planes_skewness = 0.0;  ///< a 2D cell's back and front faces
  double largest_face = 0.0;     ///< the area of its largest face
  double thickness = 0.0;        ///< a 2D cell's largest distance from back to front
};

/// One face's measures.
struct FaceMeasures {
  double non_orthogonality = 0.0;  ///< degrees; internal faces: to the neighbour, boundary: to the face centre
  double cosine = 1.0;             ///< internal faces
  double skewness = 0.0;
  double volume_ratio = 1.0;  ///< internal faces
};

/// The cells and faces of a mesh as the solver sees them (the file's cells where a mesh has
/// polyhedra), paired once, to be measured again and again while nodes move (the quality step
/// of a motion): `points` is read at every call, so moving its nodes in place is seen.
class SolverFaces {
 public:
  SolverFaces(const Mesh& mesh, std::span<const Vec3> points, const Extrusion& layer = {});
  ~SolverFaces();
  SolverFaces(const SolverFaces&) = delete;
  SolverFaces& operator=(const SolverFaces&) = delete;

  std::size_t cells() const;
  std::size_t size() const;  ///< faces
  CellId owner(std::size_t face) const;
  CellId neighbour(std::size_t face) const;  ///< -1 for a boundary face
  /// The solver's cell that cell c of Mesh::cells is (or is a piece of).
  std::size_t of_mesh_cell(std::size_t c) const;
  /// The faces of the solver's cell c (indices below size()), a 2D layer's planes not among them.
  std::span<const std::uint32_t> of_cell(std::size_t c) const;
  CellMeasures cell(std::size_t c) const;
  /// Face i between its cells as measured by cell() (`neighbour` ignored on the boundary).
  FaceMeasures face(std::size_t i, const CellMeasures& owner, const CellMeasures* neighbour) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// checkMesh's limit above which a face is "severely non-orthogonal".
inline constexpr double kSevereNonOrthogonality = 70.0;

/// The measures of every cell of `mesh` with its nodes at `points`; 2D meshes as the prisms
/// of `layer`. Parallel over cells.
SolverQuality solver_quality(const Mesh& mesh, std::span<const Vec3> points, const Extrusion& layer = {});

}  // namespace hotmesh::mesh
