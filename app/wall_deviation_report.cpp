// hotmesh app: the two-sided distance between mesh patches and their walls, for hotmesh check
// and report.json (see wall_deviation_report.hpp).
#include "wall_deviation_report.hpp"

#include <fmt/format.h>

#include <chrono>

#include "hotmesh/geometry/boundary_shapes.hpp"

namespace hotmesh::app {

namespace {

using nlohmann::json;

WallSide side(const geometry::WallDeviationPoint& p, const mesh::Mesh& mesh) {
  WallSide s;
  s.distance = p.distance;
  s.point = p.point;
  s.nearest = p.nearest;
  s.parameter = p.parameter;
  if (p.edge[0] >= 0) s.edge_nodes = {mesh.node_id(p.edge[0]), mesh.node_id(p.edge[1])};
  return s;
}

json point_json(const geometry::Vec3& p) { return {p.x, p.y, p.z}; }

json side_json(const WallSide& s, double length_scale) {
  json j{{"distance", s.distance},
         {"point", point_json(s.point)},
         {"nearest", point_json(s.nearest)},
         {"parameter", s.parameter},
         {"edge_nodes", {s.edge_nodes[0], s.edge_nodes[1]}}};
  if (length_scale > 0.0) j["distance_relative"] = s.distance / length_scale;
  return j;
}

std::string point_text(const geometry::Vec3& p) { return fmt::format("({:.9g}, {:.9g}, {:.9g})", p.x, p.y, p.z); }

}  // namespace

geometry::WallFaces wall_faces(const mesh::Patch& patch, std::span<const std::uint8_t> selected) {
  geometry::WallFaces faces;
  for (std::size_t f = 0; f < patch.faces.size(); ++f) {
    if (selected.empty() || selected[f] != 0) faces.add(patch.faces.nodes(f));
  }
  return faces;
}

std::optional<WallCheck> measure_wall(const geometry::BoundaryShape& shape, double lambda, const mesh::Mesh& mesh,
                                      std::span<const geometry::Vec3> points, const geometry::WallFaces& faces) {
  std::optional<geometry::WallDeviation> d;
  if (const auto* planar = dynamic_cast<const geometry::PlanarCurveShape*>(&shape)) {
    d = geometry::wall_deviation(planar->projector(), points, faces, {.lambda = lambda});
  } else if (const auto* revolved = dynamic_cast<const geometry::RevolvedShape*>(&shape)) {
    d = geometry::wall_deviation(revolved->projector(), points, faces, {.lambda = lambda, .axis = revolved->axis()});
  }
  if (!d) return std::nullopt;
  WallCheck w;
  w.edges = d->edges;
  w.mesh_to_shape = side(d->mesh_to_shape, mesh);
  w.shape_to_mesh = side(d->shape_to_mesh, mesh);
  w.hausdorff = d->hausdorff;
  w.worst = geometry::to_string(d->worst);
  w.parameter_range = {d->first_parameter, d->last_parameter};
  return w;
}

json wall_json(const WallCheck& wall, double length_scale) {
  json j{{"edges", wall.edges},
         {"hausdorff", wall.hausdorff},
         {"worst", wall.worst},
         {"worst_point", point_json(wall.worst_side().point)},
         {"mesh_to_shape", side_json(wall.mesh_to_shape, length_scale)},
         {"shape_to_mesh", side_json(wall.shape_to_mesh, length_scale)},
         {"parameter_range", {wall.parameter_range[0], wall.parameter_range[1]}}};
  if (length_scale > 0.0) j["hausdorff_relative"] = wall.hausdorff / length_scale;
  return j;
}

std::string wall_text(const WallCheck& wall) {
  const WallSide& s = wall.worst_side();
  const std::string where =
      wall.worst == "shape_to_mesh"
          ? fmt::format("the shape at {} is {:.3e} from the face edge of nodes {}-{}", point_text(s.point), s.distance,
                        s.edge_nodes[0], s.edge_nodes[1])
          : fmt::format("the face edge of nodes {}-{} at {} is {:.3e} from the shape", s.edge_nodes[0],
                        s.edge_nodes[1], point_text(s.point), s.distance);
  return fmt::format("two-sided distance {:.3e} over {} edges ({}: {}; mesh_to_shape {:.3e}, shape_to_mesh {:.3e})",
                     wall.hausdorff, wall.edges, wall.worst, where, wall.mesh_to_shape.distance,
                     wall.shape_to_mesh.distance);
}

json wall_deviations_json(const mesh::Mesh& mesh, std::span<const geometry::Vec3> points, const io::CaseSetup& setup,
                          double lambda, double length_scale) {
  json list = json::array();
  for (const deform::PatchMotion& motion : setup.motions) {
    const bool follows = motion.role == deform::BoundaryRole::prescribed || motion.role == deform::BoundaryRole::sliding;
    const mesh::Patch* patch = mesh.find_patch(motion.patch);
    if (!follows || !motion.shape || !patch) continue;
    const auto start = std::chrono::steady_clock::now();
    const std::optional<WallCheck> wall = measure_wall(*motion.shape, lambda, mesh, points, wall_faces(*patch));
    if (!wall) continue;
    json entry = wall_json(*wall, length_scale);
    entry["patch"] = motion.patch;
    entry["role"] = deform::to_string(motion.role);
    entry["stage"] = lambda;
    entry["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    list.push_back(std::move(entry));
  }
  return list;
}

}  // namespace hotmesh::app
