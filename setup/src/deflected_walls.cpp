// hotmesh setup: the walls of a case at a stage of the motion, as polylines and surfaces.
#include "hotmesh/setup/deflected_walls.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "hotmesh/geometry/boundary_shapes.hpp"

namespace hotmesh::setup {

using io::PolyData;
namespace {

constexpr int kCurveSamples = 2000;  ///< along a wall's curve
constexpr int kAngleSamples = 24;    ///< around the axis, over the angle of a patch

/// The angles (about `axis`) a patch's nodes cover: [first, last], through the shortest way
/// round (a sector or the whole circle).
std::pair<double, double> angle_range(const mesh::Mesh& mesh, const mesh::Patch& patch, const geometry::Axis& axis) {
  std::vector<double> angles;
  for (const mesh::NodeId n : patch.nodes) angles.push_back(axis.to_cylindrical(mesh.points[static_cast<std::size_t>(n)]).theta);
  if (angles.empty()) return {0.0, 0.0};
  std::sort(angles.begin(), angles.end());
  // The patch covers the circle but for its widest gap between neighbouring angles.
  std::size_t widest = angles.size() - 1;  // the gap across -pi / pi
  double gap = angles.front() + 2.0 * std::numbers::pi - angles.back();
  for (std::size_t i = 0; i + 1 < angles.size(); ++i) {
    if (angles[i + 1] - angles[i] > gap) {
      gap = angles[i + 1] - angles[i];
      widest = i;
    }
  }
  if (widest == angles.size() - 1) return {angles.front(), angles.back()};
  return {angles[widest + 1], angles[widest] + 2.0 * std::numbers::pi};
}

void add_polyline(PolyData& walls, std::span<const geometry::Vec2> outline, double z) {
  std::vector<std::int64_t> line;
  for (const geometry::Vec2& p : outline) {
    line.push_back(static_cast<std::int64_t>(walls.points.size()));
    walls.points.push_back({p.x, p.y, z});
  }
  walls.lines.push_back(std::move(line));
}

/// The meridional outline (r, z) revolved from angle `first` to `last`: a band of quads.
std::size_t add_revolved(PolyData& walls, std::span<const geometry::Vec2> outline, const geometry::Axis& axis,
                         std::pair<double, double> angles) {
  const auto base = static_cast<std::int64_t>(walls.points.size());
  const auto columns = static_cast<std::int64_t>(outline.size());
  for (int k = 0; k <= kAngleSamples; ++k) {
    const double theta = angles.first + (angles.second - angles.first) * k / kAngleSamples;
    for (const geometry::Vec2& p : outline) walls.points.push_back(axis.to_cartesian({p.x, theta, p.y}));
  }
  for (std::int64_t k = 0; k < kAngleSamples; ++k) {
    for (std::int64_t i = 0; i + 1 < columns; ++i) {
      const std::int64_t a = base + k * columns + i;
      walls.polygons.push_back({a, a + 1, a + 1 + columns, a + columns});
    }
  }
  return static_cast<std::size_t>(kAngleSamples) * static_cast<std::size_t>(std::max<std::int64_t>(columns - 1, 0));
}

}  // namespace

std::vector<geometry::Vec2> curve_outline(const geometry::DeflectedCurve& curve, double lambda) {
  const double a = curve.first_parameter(), b = curve.last_parameter();
  std::vector<double> parameters;
  for (int i = 0; i <= kCurveSamples; ++i) parameters.push_back(a + (b - a) * i / kCurveSamples);
  for (const geometry::DeflectedCurve::Piece& piece : curve.pieces()) parameters.push_back(piece.end);
  std::sort(parameters.begin(), parameters.end());
  parameters.erase(std::unique(parameters.begin(), parameters.end()), parameters.end());
  std::vector<geometry::Vec2> points;
  points.reserve(parameters.size());
  for (const double t : parameters) points.push_back(curve.point(t, lambda));
  return points;
}

PolyData deflected_walls(const mesh::Mesh& mesh, std::span<const deform::PatchMotion> motions, double lambda) {
  PolyData walls;
  std::vector<std::int32_t> line_patch, polygon_patch;
  for (const deform::PatchMotion& m : motions) {
    const auto it = std::find_if(mesh.patches.begin(), mesh.patches.end(), [&](const mesh::Patch& p) { return p.name == m.patch; });
    if (it == mesh.patches.end() || !m.shape) continue;
    const auto index = static_cast<std::int32_t>(it - mesh.patches.begin() + 1);
    if (const auto* planar = dynamic_cast<const geometry::PlanarCurveShape*>(m.shape.get())) {
      const double z = it->nodes.empty() ? 0.0 : mesh.points[static_cast<std::size_t>(it->nodes.front())].z;
      add_polyline(walls, curve_outline(planar->projector().curve(), lambda), z);
      line_patch.push_back(index);
    } else if (const auto* revolved = dynamic_cast<const geometry::RevolvedShape*>(m.shape.get())) {
      const std::size_t quads = add_revolved(walls, curve_outline(revolved->projector().curve(), lambda), revolved->axis(),
                                             angle_range(mesh, *it, revolved->axis()));
      polygon_patch.insert(polygon_patch.end(), quads, index);
    }
  }
  line_patch.insert(line_patch.end(), polygon_patch.begin(), polygon_patch.end());
  walls.cell_data.push_back({"patch", 1, std::move(line_patch)});
  return walls;
}

}  // namespace hotmesh::setup
