// hotmesh tests: the small systems the linear-solve tests share (test_nodal_frames.cpp,
// test_linear_solvers.cpp): an annular sector in 2D or 3D, of quads/hexes or hybrid cells, with
// fixed, sliding (one and two normals) and periodic nodes, and random admissible vectors.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "hotmesh/deform/material.hpp"
#include "hotmesh/mesh/split_cells.hpp"
#include "hotmesh/mesh/structured_mesh.hpp"
#include "hotmesh/mesh/validate.hpp"
#include "storage/linear_solver.hpp"
#include "constraints/nodal_frames.hpp"
#include "constraints/periodic.hpp"
#include "test_support.hpp"

namespace hotmesh::deform::sector_test {

using detail::ConstrainedSystem;
using detail::NodalFrames;

/// The cells of a test sector: quads (2D) or hexes (3D), or hybrid: triangles beside quads
/// (2D), prisms on the inner wall with tetrahedra and pyramids beyond (3D).
struct SectorCells {
  int dimension = 2;
  bool hybrid = false;
};

/// An annular sector about z (2D: quads in the x-y plane; 3D: hexes) with its constraints as
/// hotmesh's set-up makes them: the inner wall fixed, the outer wall sliding along tilted
/// radial normals, in 3D the bottom sliding too (nodes on the outer and bottom walls have two
/// normals), and the faces theta = 0 (masters) and theta = angle (slaves, fixed as unknowns)
/// periodic. The element matrices are computed at randomly displaced points.
struct SectorSystem {
  Mesh mesh;
  NodeConstraints constraints;
  detail::PeriodicCoupling periodic;
  StiffnessOperator stiffness;
  std::vector<Vec3> points;

  explicit SectorSystem(SectorCells cells)
      : mesh(make_mesh(cells)),
        constraints(mesh.node_count(), cells.dimension),
        periodic(static_cast<std::size_t>(cells.dimension)),
        stiffness(mesh, element_lame(mesh, {}), true),
        points(mesh.points) {
    const double angle = kAngle * std::numbers::pi / 180.0;
    const geometry::Axis z({0, 0, 0}, {0, 0, 1});
    periodic.add(mesh, *mesh.find_patch("per_lo"), *mesh.find_patch("per_hi"), z, angle, 1e-9);
    for (NodeId n : mesh.find_patch("per_hi")->nodes) constraints.fix(n);
    for (NodeId n : mesh.find_patch("inner")->nodes) constraints.fix(n);
    for (NodeId n : mesh.find_patch("outer")->nodes) {
      const Vec3& p = mesh.points[static_cast<std::size_t>(n)];
      const double tilt = 0.3 * std::sin(7.0 * p.z + 3.0 * p.y);
      constraints.constrain(n, {p.x, p.y, tilt});  // radial, tilted out of the x-y plane in 3D
    }
    if (cells.dimension == 3) {
      for (NodeId n : mesh.find_patch("bottom")->nodes) {
        const Vec3& p = mesh.points[static_cast<std::size_t>(n)];
        constraints.constrain(n, {0.2 * p.y, -0.1, 1.0});
      }
    }
    std::mt19937 random(7);
    std::uniform_real_distribution<double> jitter(-0.02, 0.02);
    for (Vec3& p : points) p += Vec3{jitter(random), jitter(random), cells.dimension == 3 ? jitter(random) : 0.0};
    stiffness.update(points);
  }

  int dimension() const { return mesh.dimension; }
  ConstrainedSystem system() const { return {stiffness.kernel(), constraints, periodic, points, {}}; }
  NodalFrames frames() const {
    NodalFrames f(mesh.node_count(), mesh.dimension);
    f.update(constraints, periodic);
    return f;
  }

  static constexpr double kAngle = 20.0;  // degrees
  static Mesh make_mesh(SectorCells cells) {
    Mesh m;
    if (cells.dimension == 3) {
      m = test::annular_sector(5, 4, 3, 1.0, 2.0, 0.0, 0.5, kAngle);
    } else {
      const auto rs = mesh::uniform_line(1.0, 2.0, 6);
      const auto ts = mesh::uniform_line(0.0, kAngle * std::numbers::pi / 180.0, 5);
      m = mesh::structured_quads(rs, ts, {"inner", "outer", "per_lo", "per_hi"});
      for (auto& p : m.points) p = {p.x * std::cos(p.y), p.x * std::sin(p.y), 0.0};
    }
    if (cells.hybrid) m = hybrid(m);
    test::jiggle_interior(m, 0.2);
    return m;
  }
  /// Cells on the inner wall kept (2D) or made prisms (3D); the others split into triangles
  /// every second cell (2D) or tetrahedra (3D).
  static Mesh hybrid(const Mesh& m) {
    std::vector<mesh::CellSplit> split(m.cell_count());
    const double wall = std::hypot(m.points[0].x, m.points[0].y) + 1e-9;
    for (std::size_t c = 0; c < split.size(); ++c) {
      const auto nodes = m.cells.nodes(c);
      const bool on_wall = std::any_of(nodes.begin(), nodes.end(), [&](NodeId n) {
        return std::hypot(m.points[static_cast<std::size_t>(n)].x, m.points[static_cast<std::size_t>(n)].y) < wall;
      });
      if (m.dimension == 2) {
        split[c] = on_wall || c % 2 ? mesh::CellSplit::keep : mesh::CellSplit::triangles;
      } else {
        split[c] = on_wall ? mesh::CellSplit::prisms : mesh::CellSplit::tetrahedra;
      }
    }
    Mesh out = mesh::split_cells(m, split);
    mesh::validate_mesh(out);
    return out;
  }
};

inline std::vector<double> random_vector(std::size_t n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<double> v(n);
  for (double& x : v) x = value(random);
  return v;
}

/// A random right-hand side in the admissible subspace of `s` (folded onto the periodic
/// masters, projected off the constrained directions), as the Newton loop hands the solvers.
inline std::vector<double> admissible_rhs(const SectorSystem& s, unsigned seed) {
  std::vector<double> rhs = random_vector(s.stiffness.size(), seed);
  s.periodic.fold(rhs);
  s.constraints.project(rhs);
  return rhs;
}

inline double max_abs(std::span<const double> v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

inline double max_difference(std::span<const double> a, std::span<const double> b) {
  double m = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

/// The unknowns of a random x~: constrained components and slaves' own rows zeroed.
inline std::vector<double> admissible(const NodalFrames& frames, std::vector<double> x) {
  std::vector<double> cartesian(x.size());
  frames.from_frames(x, cartesian);
  frames.to_frames(cartesian, x);
  return x;
}

inline std::string cells_name(SectorCells c) {
  if (c.hybrid) return c.dimension == 2 ? "TrianglesAndQuads" : "PrismsTetrahedraAndPyramids";
  return c.dimension == 2 ? "Quads" : "Hexes";
}

}  // namespace hotmesh::deform::sector_test
