// hotmesh api: the two-sided distance between mesh patches and their walls, for hotmesh check
// and report.json (see wall_deviation_report.hpp).
#include "hotmesh/api/wall_deviation_report.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <chrono>

#include "hotmesh/geometry/boundary_shapes.hpp"
#include "hotmesh/geometry/surface_shape.hpp"

namespace hotmesh::api {

namespace {

using nlohmann::json;

/// Why a wall without a surface is not measured (geometry::ScatteredShape).
constexpr const char* kScatteredReason = "the wall has no surface, only the table's interpolated displacement";

WallSide side(const geometry::WallDeviationPoint& p, const mesh::Mesh& mesh) {
  WallSide s;
  s.distance = p.distance;
  s.point = p.point;
  s.nearest = p.nearest;
  s.parameter = p.parameter;
  if (p.edge[0] >= 0) s.edge_nodes = {mesh.node_id(p.edge[0]), mesh.node_id(p.edge[1])};
  return s;
}

/// A side of a measure on faces: the mesh face's nodes, the CAD face's number and (t, s).
WallSide face_side(const geometry::WallDeviationPoint& p, const mesh::Mesh& mesh, const geometry::WallFaces& faces,
                   const geometry::SurfaceShape& shape) {
  WallSide s = side(p, mesh);
  if (p.face >= 0) {
    for (const std::int32_t n : faces.corners(static_cast<std::size_t>(p.face))) s.face_nodes.push_back(mesh.node_id(n));
  }
  s.parameter_s = p.parameter_s;
  if (p.shape_face >= 0) s.cad_face = shape.face(static_cast<std::size_t>(p.shape_face)).id;
  return s;
}

json point_json(const geometry::Vec3& p) { return {p.x, p.y, p.z}; }

json side_json(const WallSide& s, bool faces, double length_scale) {
  json j{{"distance", s.distance}, {"point", point_json(s.point)}, {"nearest", point_json(s.nearest)}};
  if (faces) {
    j["face_nodes"] = s.face_nodes;
    j["cad_face"] = s.cad_face;
    j["parameters"] = {s.parameter, s.parameter_s};
  } else {
    j["parameter"] = s.parameter;
    j["edge_nodes"] = {s.edge_nodes[0], s.edge_nodes[1]};
  }
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

WallCheck measure_wall(const geometry::BoundaryShape& shape, double lambda, const mesh::Mesh& mesh,
                       std::span<const geometry::Vec3> points, const geometry::WallFaces& faces) {
  WallCheck w;
  std::optional<geometry::WallDeviation> d;
  if (const auto* planar = dynamic_cast<const geometry::PlanarCurveShape*>(&shape)) {
    d = geometry::wall_deviation(planar->projector(), points, faces, {.lambda = lambda});
  } else if (const auto* revolved = dynamic_cast<const geometry::RevolvedShape*>(&shape)) {
    d = geometry::wall_deviation(revolved->projector(), points, faces, {.lambda = lambda, .axis = revolved->axis()});
  } else if (const auto* surface = dynamic_cast<const geometry::SurfaceShape*>(&shape)) {
    d = geometry::wall_deviation(*surface, points, faces, {.lambda = lambda});
    w.shape = "faces";
    w.faces = d->faces;
    w.shape_samples = d->shape_samples;
    w.uncovered_samples = d->uncovered_samples;
    w.mesh_to_shape = face_side(d->mesh_to_shape, mesh, faces, *surface);
    w.shape_to_mesh = face_side(d->shape_to_mesh, mesh, faces, *surface);
  } else if (dynamic_cast<const geometry::ScatteredShape*>(&shape) != nullptr) {
    w.shape = "scattered";
    w.not_measured = kScatteredReason;
    return w;
  } else {
    w.shape = "other";
    w.not_measured = "the shape is neither a curve nor CAD faces";
    return w;
  }
  if (w.shape == "curve") {
    w.edges = d->edges;
    w.mesh_to_shape = side(d->mesh_to_shape, mesh);
    w.shape_to_mesh = side(d->shape_to_mesh, mesh);
    w.parameter_range = {d->first_parameter, d->last_parameter};
  }
  w.hausdorff = d->hausdorff;
  w.worst = geometry::to_string(d->worst);
  return w;
}

std::string mesh_location(const WallSide& side) {
  if (side.face_nodes.empty()) return fmt::format("face edge of nodes {}-{}", side.edge_nodes[0], side.edge_nodes[1]);
  return fmt::format("mesh face of nodes {}", fmt::join(side.face_nodes, "-"));
}

json wall_json(const WallCheck& wall, double length_scale) {
  if (!wall.measured()) {
    return {{"shape", wall.shape}, {"measured", false}, {"reason", wall.not_measured}, {"hausdorff", nullptr}};
  }
  const bool faces = wall.shape == "faces";
  json j{{"shape", wall.shape},
         {"measured", true},
         {"hausdorff", wall.hausdorff},
         {"worst", wall.worst},
         {"worst_point", point_json(wall.worst_side().point)},
         {"mesh_to_shape", side_json(wall.mesh_to_shape, faces, length_scale)},
         {"shape_to_mesh", side_json(wall.shape_to_mesh, faces, length_scale)}};
  if (faces) {
    j["faces"] = wall.faces;
    j["shape_samples"] = wall.shape_samples;
    j["uncovered_samples"] = wall.uncovered_samples;
  } else {
    j["edges"] = wall.edges;
    j["parameter_range"] = {wall.parameter_range[0], wall.parameter_range[1]};
  }
  if (length_scale > 0.0) j["hausdorff_relative"] = wall.hausdorff / length_scale;
  return j;
}

std::string wall_text(const WallCheck& wall) {
  if (!wall.measured()) return "not measured: " + wall.not_measured;
  const WallSide& s = wall.worst_side();
  const bool faces = wall.shape == "faces";
  const std::string on_shape =
      faces ? fmt::format("the wall at {} (CAD face {}, t = {:.6g}, s = {:.6g})", point_text(wall.shape_to_mesh.point),
                          wall.shape_to_mesh.cad_face, wall.shape_to_mesh.parameter, wall.shape_to_mesh.parameter_s)
            : fmt::format("the shape at {}", point_text(s.point));
  const std::string where =
      wall.worst == "shape_to_mesh"
          ? fmt::format("{} is {:.3e} from the {}", on_shape, s.distance, mesh_location(s))
          : fmt::format("the {} at {} is {:.3e} from the {}", mesh_location(s), point_text(s.point), s.distance,
                        faces ? "wall" : "shape");
  return fmt::format("two-sided distance {:.3e} over {} {} ({}: {}; mesh_to_shape {:.3e}, shape_to_mesh {:.3e})",
                     wall.hausdorff, faces ? wall.faces : wall.edges, faces ? "faces" : "edges", wall.worst, where,
                     wall.mesh_to_shape.distance, wall.shape_to_mesh.distance);
}

json wall_deviations_json(const mesh::Mesh& mesh, std::span<const geometry::Vec3> points, const setup::CaseSetup& setup,
                          double lambda, double length_scale) {
  json list = json::array();
  for (const deform::PatchMotion& motion : setup.motions) {
    const bool follows = deform::follows_shape(motion.role);
    const mesh::Patch* patch = mesh.find_patch(motion.patch);
    if (!follows || !motion.shape || !patch) continue;
    const auto start = std::chrono::steady_clock::now();
    const WallCheck wall = measure_wall(*motion.shape, lambda, mesh, points, wall_faces(*patch));
    json entry = wall_json(wall, length_scale);
    entry["patch"] = motion.patch;
    entry["role"] = deform::to_string(motion.role);
    entry["stage"] = lambda;
    entry["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    list.push_back(std::move(entry));
  }
  return list;
}

}  // namespace hotmesh::api
