// hotmesh api: the measurements of `hotmesh check` and the check of a case (see case_check.hpp).
#include "hotmesh/api/case_check.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "hotmesh/api/mesh_summary.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/case_file.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "hotmesh/io/output_folder.hpp"

namespace hotmesh::api {
namespace {

/// Statistics of distances as they are added, node by node.
class DistanceTally {
 public:
  explicit DistanceTally(std::string reference) { check_.reference = std::move(reference); }
  void add(double d, std::int64_t node, const geometry::Vec3& p) {
    ++check_.nodes;
    sum_ += d;
    if (d > worst_ || std::isnan(d)) {
      worst_ = d;
      check_.worst_node = node;
      check_.worst_point = p;
    }
  }
  DistanceCheck result(double tolerance) const {
    DistanceCheck c = check_;
    c.max_distance = std::max(worst_, 0.0);  // NaN stays NaN
    c.mean_distance = c.nodes == 0 ? 0.0 : sum_ / static_cast<double>(c.nodes);
    c.passed = c.max_distance <= tolerance;  // false for NaN too
    return c;
  }

 private:
  DistanceCheck check_;
  double sum_ = 0.0;
  double worst_ = -1.0;
};

/// The two-sided distance of the faces of `patch` to each part of its reference: for one part
/// all faces, else each face against the part nearest to its centroid.
std::vector<WallCheck> part_walls(const mesh::Patch& patch, const mesh::Mesh& mesh,
                                                 PatchReference& reference) {
  const std::size_t parts = reference.parts.size();
  if (parts == 1) return {reference.parts[0]->wall(mesh, wall_faces(patch))};
  std::vector<std::size_t> nearest(patch.faces.size(), 0);
  for (std::size_t f = 0; f < patch.faces.size(); ++f) {
    geometry::Vec3 centroid{0, 0, 0};
    const auto corners = patch.faces.nodes(f);
    for (const mesh::NodeId n : corners) centroid = centroid + mesh.points[static_cast<std::size_t>(n)];
    centroid = centroid * (1.0 / static_cast<double>(corners.size()));
    double best = reference.parts[0]->distance(centroid);
    for (std::size_t k = 1; k < parts; ++k) {
      const double d = reference.parts[k]->distance(centroid);
      if (d < best) {
        best = d;
        nearest[f] = k;
      }
    }
  }
  std::vector<WallCheck> walls;
  for (std::size_t k = 0; k < parts; ++k) {
    std::vector<std::uint8_t> selected(patch.faces.size());
    for (std::size_t f = 0; f < selected.size(); ++f) selected[f] = nearest[f] == k ? 1 : 0;
    walls.push_back(reference.parts[k]->wall(mesh, wall_faces(patch, selected)));
  }
  return walls;
}

/// Sets `check.wall` and folds the wall tolerance into `check.passed`.
void put_wall(DistanceCheck& check, WallCheck wall, const std::optional<double>& wall_tolerance) {
  if (wall.measured() && wall_tolerance) wall.passed = wall.hausdorff <= *wall_tolerance;  // false for NaN too
  check.wall = std::move(wall);
  if (!check.wall.passed) check.passed = false;
}

bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code ec;
  const bool same = std::filesystem::equivalent(a, b, ec);
  return !ec && same;
}

}  // namespace

double default_tolerance(const mesh::Mesh& mesh) {
  geometry::Vec3 lo = mesh.points.front(), hi = lo;
  for (const auto& p : mesh.points) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  }
  return 1e-6 * geometry::distance(lo, hi);
}

/// The nodes of `patch` measured against its reference, each node against the nearest part;
/// then its faces, both ways.
PatchCheck check_patch(const mesh::Patch& patch, const mesh::Mesh& mesh, PatchReference& reference,
                       double tolerance, const std::optional<double>& wall_tolerance) {
  const auto start = std::chrono::steady_clock::now();
  DistanceTally whole(reference.description);
  std::vector<DistanceTally> parts;
  for (const auto& part : reference.parts) parts.emplace_back(part->description());
  for (const mesh::NodeId n : patch.nodes) {
    const geometry::Vec3& p = mesh.points[static_cast<std::size_t>(n)];
    std::size_t nearest = 0;
    double d = reference.parts[0]->distance(p);
    for (std::size_t k = 1; k < reference.parts.size(); ++k) {
      const double dk = reference.parts[k]->distance(p);
      if (dk < d) {
        d = dk;
        nearest = k;
      }
    }
    whole.add(d, mesh.node_id(n), p);
    parts[nearest].add(d, mesh.node_id(n), p);
  }
  PatchCheck check;
  static_cast<DistanceCheck&>(check) = whole.result(tolerance);
  check.patch = patch.name;
  std::vector<WallCheck> walls = part_walls(patch, mesh, reference);
  if (parts.size() > 1) {
    for (std::size_t k = 0; k < parts.size(); ++k) {
      check.parts.push_back(parts[k].result(tolerance));
      put_wall(check.parts.back(), walls[k], wall_tolerance);
    }
  }
  // The patch's: the largest of its parts' (a part not measured leaves the patch unmeasured).
  WallCheck worst = walls[0];
  for (std::size_t k = 1; k < walls.size() && worst.measured(); ++k) {
    if (!walls[k].measured() || walls[k].hausdorff > worst.hausdorff || std::isnan(walls[k].hausdorff)) worst = walls[k];
  }
  put_wall(check, std::move(worst), wall_tolerance);
  check.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return check;
}

void log_patch(const PatchCheck& p) {
  spdlog::info("{}: {} nodes, max distance {:.3e} at node {}, mean {:.3e}; faces {} ({})", p.patch, p.nodes,
               p.max_distance, p.worst_node, p.mean_distance,
               p.wall.measured() ? fmt::format("{:.3e} both ways", p.wall.hausdorff)
                                            : std::string("not measured"),
               p.passed ? "pass" : "FAIL");
}

CheckResult check_with_case(const CaseCheckOptions& o, std::vector<std::filesystem::path>& inputs, bool& inputs_known) {
  const io::Case c = io::read_case(o.case_file.string());
  for (const auto& file : c.inputs()) inputs.push_back(file);
  inputs_known = true;
  const std::filesystem::path mesh_path = o.mesh.empty() ? c.mesh : o.mesh;
  if (!o.output.empty()) io::refuse_overwriting_input(o.output, inputs);

  const bool own_mesh = o.mesh.empty() || same_file(o.mesh, c.mesh);
  const io::LoadedMesh case_mesh = io::read_mesh(c.mesh);
  std::optional<io::LoadedMesh> deformed;
  if (!own_mesh) {
    deformed.emplace(io::read_mesh(mesh_path));
    if (deformed->mesh.points.size() != case_mesh.mesh.points.size() ||
        deformed->mesh.dimension != case_mesh.mesh.dimension) {
      throw InputError::in(mesh_path.string(),
                           fmt::format("{} nodes in {}D, but the case's mesh {} has {} nodes in {}D: give a mesh the "
                                       "case was deformed into (hotmesh deform's deformed.msh)",
                                       deformed->mesh.points.size(), deformed->mesh.dimension, c.mesh.string(),
                                       case_mesh.mesh.points.size(), case_mesh.mesh.dimension));
    }
  }
  const mesh::Mesh& mesh = deformed ? deformed->mesh : case_mesh.mesh;
  std::vector<CasePatchReference> references =
      case_references(c, case_mesh.mesh, own_mesh ? CaseStage::undeformed : CaseStage::deflected);
  if (references.empty()) {
    throw InputError::in(c.file.string(), "no patch follows a boundary (role prescribed or sliding): nothing to check");
  }

  CheckResult result;
  result.mesh = mesh_path.string();
  result.quality = mesh_quality_json(deformed ? *deformed : case_mesh);
  result.case_file = o.case_file.string();
  result.cad = c.cad ? c.cad->string() : std::string();
  result.unit = geometry::to_string(c.length_unit);
  result.tolerance = o.tolerance > 0.0 ? o.tolerance : default_tolerance(mesh);
  result.wall_tolerance = o.wall_tolerance;
  for (CasePatchReference& r : references) {
    const mesh::Patch* patch = mesh.find_patch(r.patch);
    const mesh::Patch* original = case_mesh.mesh.find_patch(r.patch);
    if (!patch || patch->nodes.size() != original->nodes.size()) {
      throw InputError::in(mesh_path.string(),
                           fmt::format("patch '{}' {} in the case's mesh {}: give a mesh the case was deformed into",
                                       r.patch, patch ? "has other nodes than" : "is missing; it is", c.mesh.string()));
    }
    result.patches.push_back(check_patch(*patch, mesh, r.reference, result.tolerance, result.wall_tolerance));
    log_patch(result.patches.back());
  }
  return result;
}

}  // namespace hotmesh::api
