// hotmesh mesh (internal): the cells a flow solver sees, as the outward polygons of their
// faces, for solver_quality.cpp: the mesh's cells (a 2D mesh's cells as the prisms of its
// layer), or, in a mesh with polyhedra, the file's cells, a polyhedron with its own faces
// (mesh::Polyhedra) rather than its pieces; and the faces where they meet.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "hotmesh/mesh/mesh_topology.hpp"
#include "hotmesh/mesh/solver_quality.hpp"

namespace hotmesh::mesh::detail {

/// A face's points in order, up to four in place, more (a polyhedron's face) on the heap.
class Polygon {
 public:
  int size() const { return n_; }
  void resize(int n) {
    n_ = n;
    if (n > kSmall) large_.resize(static_cast<std::size_t>(n));
  }
  Vec3& operator[](int k) { return n_ > kSmall ? large_[static_cast<std::size_t>(k)] : small_[static_cast<std::size_t>(k)]; }
  const Vec3& operator[](int k) const {
    return n_ > kSmall ? large_[static_cast<std::size_t>(k)] : small_[static_cast<std::size_t>(k)];
  }
  std::span<const Vec3> points() const {
    return n_ > kSmall ? std::span<const Vec3>(large_) : std::span<const Vec3>(small_.data(), static_cast<std::size_t>(n_));
  }

 private:
  static constexpr int kSmall = 4;
  std::array<Vec3, kSmall> small_{};
  std::vector<Vec3> large_;
  int n_ = 0;
};

/// How a 2D mesh's cells stand in 3D, and which Cartesian axes the aspect ratio compares.
struct Layer {
  bool planar = false;  // a 2D mesh, measured as the prisms of `extrusion`
  Extrusion extrusion;
  std::array<bool, 3> axes{true, true, true};
  Vec3 back(const Vec3& p) const { return extrusion.back.at(p); }
  Vec3 front(const Vec3& p) const { return extrusion.front.at(p); }
};
Layer layer_of(const Mesh& mesh, std::span<const Vec3> points, const Extrusion& extrusion);

/// A face of the mesh: an internal face between `owner` and `neighbour`, or a boundary face
/// (neighbour.cell < 0); `owner` is the cell with the lower number.
struct MeshFace {
  CellFace owner;
  CellFace neighbour{-1, 0};
};

class SolverCells {
 public:
  SolverCells(const Mesh& mesh, std::span<const Vec3> points, const Layer& layer);

  /// The mesh's cells, or its file's cells if it has polyhedra (Mesh::cells[c] for c below
  /// that number is file cell c or its first piece).
  std::size_t size() const { return count_; }
  /// The faces of cell c (3D), or its edges (2D: the sides of its prism).
  int side_count(std::size_t c) const;
  Polygon polygon(std::size_t c, int local) const;
  /// The back and front faces of a 2D cell's prism.
  std::array<Polygon, 2> planes(std::size_t c) const;
  /// The cell's element type; none for a polyhedron.
  std::optional<ElementType> type(std::size_t c) const;
  std::vector<MeshFace> faces() const;
  /// The cell of size() that mesh cell c is (or is a piece of).
  std::size_t of_mesh_cell(std::size_t c) const { return static_cast<std::size_t>(mesh_.polyhedra.file_cell(static_cast<CellId>(c))); }
  const Layer& layer() const { return layer_; }

 private:
  std::span<const NodeId> polyhedron_face(std::size_t c, int local) const;
  std::vector<MeshFace> polyhedral_faces() const;

  const Mesh& mesh_;
  std::span<const Vec3> points_;
  Layer layer_;
  std::size_t count_ = 0;
  std::vector<std::int32_t> polyhedron_;  ///< per cell, its index in mesh.polyhedra, or -1
};

}  // namespace hotmesh::mesh::detail
