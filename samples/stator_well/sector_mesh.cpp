// hotmesh sample stator_well: mesh sizes, and the meridional quads swept in theta into the
// hexahedra of the 3.6 degree sector with its named patches.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "stator_well.hpp"

namespace hotmesh::samples::stator_well {

Size size_at(const BlockMesher& mesher, double refinement) {
  Size s;
  s.refinement = refinement;
  s.theta_cells = std::max(3, static_cast<int>(std::lround(3.6 * refinement)));
  s.quads = mesher.quad_count(refinement);
  s.cells = s.quads * s.theta_cells;
  s.nodes = mesher.node_count(refinement) * (s.theta_cells + 1);
  return s;
}

Size size_for_cells(const BlockMesher& mesher, std::int64_t cells) {
  // Counts grow with s (up to rounding of each class's count): bisect on log s.
  double lo = 0.05, hi = 100.0;
  for (int it = 0; it < 60; ++it) {
    const double mid = std::sqrt(lo * hi);
    (size_at(mesher, mid).cells < cells ? lo : hi) = mid;
  }
  const Size below = size_at(mesher, lo), above = size_at(mesher, hi);
  return cells - below.cells < above.cells - cells ? below : above;
}

mesh::Mesh sector_mesh(const QuadMesh& section, const std::vector<ProfileCurve>& loop, int theta_cells) {
  using mesh::ElementType;
  using mesh::NodeId;
  mesh::Mesh mesh;
  mesh.dimension = 3;
  const auto layer_nodes = static_cast<NodeId>(section.nodes.size());
  const auto layers = static_cast<std::size_t>(theta_cells) + 1;
  const double angle = kSectorDegrees * std::numbers::pi / 180.0;

  // Nodes layer by layer: (z, r) at theta_k = angle k / n, about the z axis (theta = 0 along x).
  mesh.points.reserve(layers * section.nodes.size());
  for (int k = 0; k <= theta_cells; ++k) {
    const double theta = k == theta_cells ? angle : angle * k / theta_cells;
    const double c = std::cos(theta), s = std::sin(theta);
    for (const Vec2& zr : section.nodes) mesh.points.push_back({zr.y * c, zr.y * s, zr.x});
  }
  const auto node = [&](std::int32_t m, int k) { return static_cast<NodeId>(k) * layer_nodes + m; };

  // Hexes: a quad counter-clockwise in (z, r) has its normal along +theta (e_z x e_r = e_theta),
  // so layer k then layer k + 1 gives positive corner Jacobians.
  mesh.cells.reserve(section.quads.size() * static_cast<std::size_t>(theta_cells),
                     8 * section.quads.size() * static_cast<std::size_t>(theta_cells));
  for (int k = 0; k < theta_cells; ++k) {
    for (const auto& q : section.quads) {
      mesh.cells.add(ElementType::hex8, {node(q[0], k), node(q[1], k), node(q[2], k), node(q[3], k), node(q[0], k + 1),
                                         node(q[1], k + 1), node(q[2], k + 1), node(q[3], k + 1)});
    }
  }

  // Patches in Patch order. A wall segment a -> b runs with the fluid on its left, so
  // (a_k, b_k, b_k+1, a_k+1) has its normal out of the fluid; the periodic faces are the
  // quads of the first layer turned over and those of the last layer.
  for (int p = 0; p < kPatchCount; ++p) {
    mesh::Patch patch;
    patch.name = std::string(name(static_cast<Patch>(p)));
    patch.tag = p + 1;
    mesh.patches.push_back(std::move(patch));
  }
  for (const auto& segment : section.boundary) {
    auto& faces = mesh.patches[static_cast<std::size_t>(loop[static_cast<std::size_t>(segment.curve)].patch)].faces;
    for (int k = 0; k < theta_cells; ++k) {
      faces.add(ElementType::quad4, {node(segment.a, k), node(segment.b, k), node(segment.b, k + 1), node(segment.a, k + 1)});
    }
  }
  auto& lo = mesh.patches[static_cast<std::size_t>(Patch::per_lo)].faces;
  auto& hi = mesh.patches[static_cast<std::size_t>(Patch::per_hi)].faces;
  for (const auto& q : section.quads) {
    lo.add(ElementType::quad4, {node(q[0], 0), node(q[3], 0), node(q[2], 0), node(q[1], 0)});
    hi.add(ElementType::quad4, {node(q[0], theta_cells), node(q[1], theta_cells), node(q[2], theta_cells), node(q[3], theta_cells)});
  }
  mesh::CellGroup fluid;
  fluid.name = "fluid";
  fluid.tag = kPatchCount + 1;
  fluid.cells.resize(mesh.cells.size());
  for (std::size_t c = 0; c < fluid.cells.size(); ++c) fluid.cells[c] = static_cast<mesh::CellId>(c);
  mesh.cell_groups.push_back(std::move(fluid));
  mesh.derive_node_sets();
  return mesh;
}

}  // namespace hotmesh::samples::stator_well
