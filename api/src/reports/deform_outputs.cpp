// hotmesh api: what `hotmesh deform` writes to its output folder (see deform_outputs.hpp).
#include "hotmesh/api/deform_outputs.hpp"
#include "hotmesh/api/series_outputs.hpp"

#include "hotmesh/parallel/processes.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <numbers>

#include <nlohmann/json.hpp>

#include "hotmesh/deform/move_mesh.hpp"
#include "hotmesh/geometry/surface_shape.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/figure.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/io/mesh_picture.hpp"
#include "hotmesh/io/vtu.hpp"
#include "hotmesh/api/mesh_summary.hpp"
#include "hotmesh/api/wall_deviation_report.hpp"

namespace hotmesh::api {
namespace {

/// The quality fields (`fields`) with the displacement and each node's role.
io::VtuFields deform_fields(io::VtuFields fields, const mesh::Mesh& mesh, const std::vector<geometry::Vec3>& points,
                            const deform::MotionResult& result) {
  std::vector<double> displacement;
  displacement.reserve(3 * points.size());
  for (std::size_t n = 0; n < points.size(); ++n) {
    const geometry::Vec3 d = points[n] - mesh.points[n];
    displacement.insert(displacement.end(), {d.x, d.y, d.z});
  }
  fields.point_data.push_back({"displacement", 3, std::move(displacement)});
  std::vector<std::int32_t> roles(result.node_roles.begin(), result.node_roles.end());
  fields.point_data.push_back({"node_role", 1, std::move(roles)});
  return fields;
}

/// A picture of a 2D mesh coloured by quality, with the deflected boundaries as given by the
/// FEM tables drawn in blue over it (as in the paper's figures).
void picture(const std::filesystem::path& path, const std::string& title, const mesh::Mesh& mesh,
             const std::vector<geometry::Vec3>& points, const std::vector<double>& quality,
             const setup::CaseSetup& setup, const io::PictureView* view) {
  io::Figure figure({.width = 1400, .height = 900, .title = title, .x_label = "x", .y_label = "y"});
  io::draw_mesh(figure, mesh, points, {.edges = {io::colors::black, view ? 0.8 : 0.4}, .quality = quality});
  for (const auto& shape : setup.shapes) {
    std::vector<io::PlotPoint> line;
    for (const auto& p : shape.deflected_outline) line.push_back({p.x, p.y});
    figure.polyline(line, {io::colors::blue, 2.0});
  }
  if (!setup.shapes.empty()) figure.legend("deflected wall (FEM)", {io::colors::blue, 2.0});
  if (view) figure.set_view(view->xmin, view->xmax, view->ymin, view->ymax);
  figure.save(path);
}

}  // namespace

std::uint64_t peak_memory_bytes() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) * 1024;  // kB
  }
  return 0;
}

std::vector<std::string> output_names(const io::Case& c, const io::LoadedMesh& loaded) {
  const mesh::Mesh& mesh = loaded.mesh;
  std::vector<std::string> names{"deformed.msh", "deformed.vtu", "failed.vtu", "report.json", "restart.hmr",
                                 std::string(io::kCheckpointName)};
  if (loaded.write_back) {
    for (std::string& name : loaded.write_back->output_names()) names.push_back(std::move(name));
  }
  for (std::string& name : SeriesWriter::output_names()) names.push_back(std::move(name));
  if (mesh.dimension == 2) {
    names.push_back("deformed.png");
    names.push_back("failed.png");
    for (const auto& p : c.pictures) names.push_back(p.name + ".png");
  }
  return names;
}

std::string failure_text(const deform::MotionFailure& failure) {
  switch (failure.kind) {
    case deform::MotionFailure::Kind::inverted_cells: return "cells inverted (dark red)";
    case deform::MotionFailure::Kind::newton_stalled: return "Newton did not converge; no cell inverted";
    case deform::MotionFailure::Kind::newton_diverged: return "Newton diverged; no cell inverted";
    case deform::MotionFailure::Kind::linear_breakdown: return "the linear solver broke down; no cell inverted";
    case deform::MotionFailure::Kind::quality_limits: return "cells beyond the case's quality limits; no cell inverted";
    case deform::MotionFailure::Kind::none: break;
  }
  return "it did not fail";
}

RunOutputs write_outputs(const std::filesystem::path& folder, const io::Case& c, const io::LoadedMesh& loaded,
                         const setup::CaseSetup& setup, const deform::MotionResult& result,
                         const mesh::SolverQuality& solver, bool binary_msh, const io::WriteBackOptions& write_back) {
  RunOutputs out;
  const mesh::Mesh& mesh = loaded.mesh;
  mesh::Mesh moved = mesh;
  moved.points = result.points;
  io::write_gmsh(folder / "deformed.msh", moved, {.binary = binary_msh});
  out.files.push_back(folder / "deformed.msh");
  if (loaded.write_back) {
    for (auto& path : loaded.write_back->write(folder, result.points, write_back)) out.files.push_back(std::move(path));
  }
  io::write_vtu(folder / "deformed.vtu", mesh, result.points,
                deform_fields(io::quality_fields(mesh, result.points, solver), mesh, result.points, result));
  out.files.push_back(folder / "deformed.vtu");
  if (!result.success) {
    io::VtuFields fields =
        deform_fields(io::quality_fields(mesh, result.failed_points, loaded.layer), mesh, result.failed_points, result);
    if (!result.failure.residual.empty()) fields.point_data.push_back({"newton_residual", 1, result.failure.residual});
    io::write_vtu(folder / "failed.vtu", mesh, result.failed_points, fields);
    out.files.push_back(folder / "failed.vtu");
  }
  if (mesh.dimension == 2) {
    const std::string name = c.file.stem().string();
    const std::string stage = result.success ? "" : fmt::format(" at stage {:.3f} (last valid)", result.lambda_reached);
    const std::string title =
        fmt::format("{}: deformed mesh{}, min scaled Jacobian {:.3f}, max non-orthogonality {:.1f} deg, max skewness {:.2f}",
                    name, stage, result.summary.min_scaled_jacobian, solver.summary.max_non_orthogonality.value,
                    solver.summary.max_skewness.value);
    picture(folder / "deformed.png", title, mesh, result.points, result.quality, setup, nullptr);
    out.files.push_back(folder / "deformed.png");
    for (const auto& view : c.pictures) {
      picture(folder / (view.name + ".png"), fmt::format("{}: {}", name, view.name), mesh, result.points,
              result.quality, setup, &view);
      out.files.push_back(folder / (view.name + ".png"));
    }
    if (!result.success) {
      picture(folder / "failed.png", fmt::format("{}: the failed increment: {}", name, failure_text(result.failure)), mesh,
              result.failed_points, result.failed_quality, setup, nullptr);
      out.files.push_back(folder / "failed.png");
    }
  }
  return out;
}

namespace {

using nlohmann::json;

/// Every length `key` in mesh units has a `key_relative`: divided by `scale`, the diagonal of
/// the undeformed mesh's bounding box.
void put_length(json& object, const std::string& key, double length, double scale) {
  object[key] = length;
  object[key + "_relative"] = length / scale;
}

/// Where a `calculix:` table came from: files, set, the output step read and the set's
/// temperatures at that step (when the .frd has them).
json calculix_json(const io::CalculixNote& note) {
  json j{{"frd", note.selection.frd.string()}, {"inp", note.selection.inp.string()}, {"set", note.selection.set},
         {"model", io::to_string(note.kind)},  {"step", note.step},                  {"time", note.time}};
  if (note.min_temperature) j["min_temperature"] = *note.min_temperature;
  if (note.max_temperature) j["max_temperature"] = *note.max_temperature;
  return j;
}

json deflections_json(const io::Case& c, const setup::CaseSetup& setup, double scale) {
  json deflections = json::array();
  for (const auto& s : setup.shapes) {
    const auto& r = s.reconstruction;
    json deflection{{"patch", s.patch},
                    {"nodes", r.nodes},
                    {"used_nodes", r.used_nodes},
                    {"merged_duplicates", r.merged_duplicates},
                    {"degree", r.degree},
                    {"form", geometry::to_string(r.form)}};
    put_length(deflection, "max_node_distance_to_cad", r.max_node_distance_to_cad, scale);
    put_length(deflection, "max_node_residual", r.max_node_residual, scale);
    deflection["wall"] = setup::kWallKindNames.name(s.kind);
    if (s.faces) {
      put_length(deflection, "max_edge_gap", s.faces->max_edge_gap, scale);
      deflection["shared_edges"] = s.faces->shared_edges;
      deflection["joined_edges"] = s.faces->joined_edges;
      json faces = json::array();
      for (const auto& f : s.faces->faces) {
        json face{{"face", f.face},
                  {"nodes", f.nodes},
                  {"method", f.fit.method == geometry::SurfaceFitMethod::interpolation ? "interpolation" : "least_squares"},
                  {"poles", {f.fit.u_poles, f.fit.v_poles}}};
        put_length(face, "max_node_residual", f.fit.max_residual, scale);
        faces.push_back(std::move(face));
      }
      deflection["faces"] = std::move(faces);
    }
    if (s.scattered) {
      deflection["interpolation"] = {{"method", "partition-of-unity RBF"},
                                     {"patches", s.scattered->patches},
                                     {"largest_patch", s.scattered->largest_patch}};
    }
    if (s.linear) {
      deflection["interpolation"] = {{"method", "linear over triangles"}, {"triangles", s.linear->triangles}};
    }
    const io::PatchSpec* spec = c.find_patch(s.patch);
    if (spec != nullptr && spec->deflection && spec->deflection->calculix) {
      deflection["calculix"] = calculix_json(*spec->deflection->calculix);
    }
    deflections.push_back(std::move(deflection));
  }
  return deflections;
}

json solver_json(const deform::SolverOptions& solver, const deform::LinearSolverChoice& linear) {
  return {{"increments", solver.increments},
          {"newton_tolerance", solver.newton_tolerance},
          {"max_newton_iterations", solver.max_newton_iterations},
          {"pcg_tolerance", solver.pcg_tolerance},
          {"max_pcg_iterations", solver.max_pcg_iterations},
          {"max_increment_splits", solver.max_increment_splits},
          {"linear", deform::to_string(linear.kind)},
          {"linear_chosen_by", solver.linear == deform::LinearSolverKind::automatic ? fmt::format("auto: {}", linear.reason)
                                                                                  : std::string(linear.reason)},
          {"amg", deform::to_string(solver.amg)},
          {"amg_reuse", deform::kAmgReuseNames.name(solver.amg_reuse)},
          {"forcing", deform::to_string(solver.forcing)},
          {"predictor", solver.predictor},
          {"processes", parallel::processes().count}};
}

/// One attempt of an increment, with its Newton steps.
json attempt_json(const deform::IncrementRecord& r, const deform::MotionResult& result) {
  const double scale = result.length_scale;
  json pcg = json::array(), tolerances = json::array(), norms = json::array(), residuals = json::array(),
       projections = json::array(), relative_projections = json::array();
  for (std::size_t i = 0; i < r.newton.size(); ++i) {
    residuals.push_back(r.newton[i].residual);
    if (i + 1 < r.newton.size() && result.sliding_nodes > 0) {
      projections.push_back(r.newton[i].max_projection);
      relative_projections.push_back(r.newton[i].max_projection / scale);
    }
    if (i + 1 < r.newton.size()) {
      pcg.push_back(r.newton[i].pcg_iterations);
      tolerances.push_back(r.newton[i].linear_tolerance);
      norms.push_back(r.newton[i].linear_newton_norm ? "newton" : "residual");
    }
  }
  json attempt{{"increment", r.increment},
               {"corner_pass", r.corner_pass},
               {"stage", {r.lambda_begin, r.lambda_end}},
               {"split_depth", r.split_depth},
               {"accepted", r.accepted},
               {"converged", r.converged},
               {"newton_iterations", r.newton.empty() ? 0 : r.newton.size() - 1},
               {"pcg_iterations", pcg},
               {"linear_tolerances", tolerances},
               {"linear_norms", norms},
               {"residuals", residuals},
               {"residual_reduction", r.residual_reduction},
               // The quality is checked only once Newton has converged: unknown otherwise.
               {"min_scaled_jacobian", r.converged ? json(r.min_scaled_jacobian) : json(nullptr)},
               {"inverted_cells", r.converged ? json(r.inverted_cells) : json(nullptr)},
               {"max_projection_distance", projections},
               {"max_projection_distance_relative", relative_projections},
               {"smoothed_nodes", r.smoothed_nodes},
               {"seconds", r.seconds},
               {"failure", r.failure}};
  put_length(attempt, "max_normal_slip", r.max_normal_slip, scale);
  return attempt;
}

/// The increments' attempts, and the run's totals of Newton and PCG iterations.
void put_increments(json& j, const deform::MotionResult& result) {
  j["increments"] = json::array();
  std::size_t newton_total = 0, pcg_total = 0;
  for (const auto& r : result.increments) {
    for (const auto& step : r.newton) pcg_total += static_cast<std::size_t>(step.pcg_iterations);
    newton_total += r.newton.empty() ? 0 : r.newton.size() - 1;
    j["increments"].push_back(attempt_json(r, result));
  }
  j["newton_iterations"] = newton_total;
  j["pcg_iterations"] = pcg_total;
}

/// The corners of the sliding walls and the nodes that hold them (the corner pass).
/// The CAD face numbers of a crease of a wall made of faces (WallFeature::faces holds the
/// faces' indices in the wall's shape).
json crease_faces(const setup::CaseSetup& setup, const deform::WallFeature& f) {
  json faces = json::array();
  const auto motion = std::find_if(setup.motions.begin(), setup.motions.end(),
                                   [&](const deform::PatchMotion& m) { return m.patch == f.patch; });
  const auto* wall = motion == setup.motions.end() ? nullptr
                                                   : dynamic_cast<const geometry::SurfaceShape*>(motion->shape.get());
  for (const int i : f.faces) {
    const bool known = wall != nullptr && i >= 0 && static_cast<std::size_t>(i) < wall->face_count();
    faces.push_back(known ? wall->face(static_cast<std::size_t>(i)).id : i);
  }
  return faces;
}

json features_json(const mesh::Mesh& mesh, const setup::CaseSetup& setup, const deform::MotionResult& result) {
  json features = json::array();
  for (const deform::WallFeature& f : result.features) {
    json nodes = json::array();
    for (const mesh::NodeId n : f.nodes) nodes.push_back(mesh.node_id(n));
    json feature{{"patch", f.patch},
                 {"kind", f.faces.empty() ? "corner" : "crease"},
                 {"parameter", f.parameter},
                 {"angle_deg", f.angle * 180.0 / std::numbers::pi},
                 {"point", {f.point.x, f.point.y, f.point.z}},
                 {"nodes", nodes},
                 {"given_nodes", f.given_nodes},
                 {"held", f.from_start ? "from_start" : "corner_pass"},
                 {"unheld_edges", f.unheld_edges}};
    put_length(feature, "largest_offset", f.largest_offset, result.length_scale);
    put_length(feature, "distance", f.distance, result.length_scale);
    if (!f.faces.empty()) feature["faces"] = crease_faces(setup, f);
    features.push_back(std::move(feature));
  }
  return features;
}

/// The motion's results: stage, node counts, memory, the lengths and the quality.
void put_motion(json& j, const mesh::Mesh& mesh, const setup::CaseSetup& setup, const deform::MotionResult& result,
                const mesh::SolverQuality& solver) {
  const double scale = result.length_scale;
  j["stage_reached"] = result.lambda_reached;
  j["sliding_nodes"] = result.sliding_nodes;
  j["passive_nodes"] = result.passive_nodes;
  j["periodic_pairs"] = result.periodic_pairs;
  j["peak_memory_bytes"] = peak_memory_bytes();
  j["length_scale"] = scale;
  put_length(j, "max_periodic_mismatch", result.max_periodic_mismatch, scale);
  put_length(j, "max_projection_distance", result.max_projection_distance, scale);
  put_length(j, "final_projection_distance", result.final_projection_distance, scale);
  put_length(j, "max_normal_slip", result.max_normal_slip, scale);
  // Deprecated (docs/report-json.md): written as before for one more version.
  j["periodic_max_mismatch"] = j["max_periodic_mismatch_relative"];
  j["max_sliding_projection_distance"] = j["final_projection_distance_relative"];
  j["min_scaled_jacobian"] = result.summary.min_scaled_jacobian;
  j["inverted_cells"] = result.summary.inverted_cells;
  j["quality"] = quality_json(mesh, result.points, result.summary, result.quality, solver);
  j["notes"] = result.notes;
  j["features"] = features_json(mesh, setup, result);
  const auto& repair = result.corner_repair;
  j["corner_repair"] = {{"cells_below", repair.cells_below},
                        {"nodes_moved", repair.nodes_moved},
                        {"min_before", repair.min_before},
                        {"min_after", repair.min_after}};
}

json threads_json(const RunThreads& threads) {
  const parallel::ThreadChoice& c = threads.choice;
  return {{"count", c.threads},
          {"reason", c.reason},
          {"chosen_by", threads.inputs.request.count > 0 ? "the user" : "hotmesh"},
          {"cores", threads.inputs.cores},
          {"other_load", c.others_busy ? json(*c.others_busy) : json(nullptr)},
          {"wait_policy", threads.wait}};
}

json seconds_json(const RunTimings& timings, const deform::MotionTimings& m) {
  return {{"read", timings.read},         {"shapes", timings.shapes},   {"setup", m.setup},
          {"assembly", m.assembly},       {"preconditioner", m.preconditioner},
          {"solve", m.solve},             {"projection", m.projection}, {"quality", m.quality},
          {"motion", m.total},            {"checkpoint", timings.checkpoint},
          {"write", timings.write}};
}

}  // namespace

deform::LinearSolverChoice linear_solver_of(const io::Case& c, const mesh::Mesh& mesh, const setup::CaseSetup& setup) {
  if (c.solver.linear != deform::LinearSolverKind::automatic) return {c.solver.linear, "the case file"};
  return deform::choose_linear_solver(mesh, setup.motions, parallel::processes().count);
}

namespace {

/// Each patch's role; for a prescribed or sliding patch, how far its nodes lay from its
/// undeformed wall before the motion put them on it.
json patches_json(const mesh::Mesh& mesh, const setup::CaseSetup& setup, const deform::MotionResult& result) {
  json patches = json::array();
  for (const auto& m : setup.motions) {
    json patch{{"name", m.patch}, {"role", deform::to_string(m.role)}};
    const auto gap = std::find_if(result.wall_gaps.begin(), result.wall_gaps.end(),
                                  [&](const deform::WallGap& g) { return g.patch == m.patch; });
    if (gap != result.wall_gaps.end() && gap->node >= 0) {
      put_length(patch, "undeformed_gap", gap->distance, result.length_scale);
      patch["undeformed_gap_node"] = mesh.node_id(gap->node);
    }
    patches.push_back(std::move(patch));
  }
  return patches;
}

/// What a failed run ran into, and the nodes where its last Newton residual is largest.
json failure_json(const mesh::Mesh& mesh, const deform::MotionResult& result) {
  static constexpr std::array<const char*, 6> kinds{"none", "inverted_cells", "newton_stalled", "newton_diverged",
                                                    "linear_breakdown", "quality_limits"};
  json nodes = json::array();
  for (const auto& r : result.failure.largest_residuals) {
    const geometry::Vec3& x = result.failed_points[static_cast<std::size_t>(r.node)];
    json node{{"node", mesh.node_id(r.node)}, {"point", {x.x, x.y, x.z}}};
    put_length(node, "residual", r.residual, result.length_scale);
    nodes.push_back(std::move(node));
  }
  return {{"kind", kinds[static_cast<std::size_t>(result.failure.kind)]}, {"largest_residuals", std::move(nodes)}};
}

}  // namespace

std::string deform_report(const std::filesystem::path& folder, const io::Case& c, const io::LoadedMesh& loaded,
                          const setup::CaseSetup& setup, const deform::MotionResult& result,
                          const mesh::SolverQuality& solver, const RunTimings& timings, const RunThreads& threads,
                          const RunOutputs& outputs, const io::CheckpointInfo* resumed) {
  json j;
  j["hotmesh_version"] = HOTMESH_VERSION;
  j["command"] = "deform";
  j["case"] = c.file.string();
  j["status"] = result.success ? "success" : "failed";
  j["message"] = result.message;
  j["mesh"] = mesh_summary(loaded, c.mesh);
  j["patches"] = patches_json(loaded.mesh, setup, result);
  if (!result.success) j["failure"] = failure_json(loaded.mesh, result);
  j["deflections"] = deflections_json(c, setup, result.length_scale);
  j["solver"] = solver_json(c.solver, linear_solver_of(c, loaded.mesh, setup));
  j["threads"] = threads_json(threads);
  put_increments(j, result);
  put_motion(j, loaded.mesh, setup, result, solver);
  j["peak_memory_bytes_all_ranks"] = std::max(timings.peak_memory_all_ranks, j["peak_memory_bytes"].get<std::uint64_t>());
  j["wall_deviations"] = wall_deviations_json(loaded.mesh, result.points, setup, result.lambda_reached, result.length_scale);
  if (c.restart) j["restarted_from"] = c.restart->string();
  if (resumed) {
    j["resumed_from"] = {{"checkpoint", (folder / io::kCheckpointName).string()},
                         {"written_at", resumed->written_at},
                         {"finished_increments", resumed->finished_increments},
                         {"stage", resumed->lambda}};
  }
  j["checkpoints"] = {{"written", timings.checkpoints},
                      {"seconds", timings.checkpoint},
                      {"last_bytes", timings.checkpoint_bytes}};
  j["seconds"] = seconds_json(timings, result.timings);
  j["wall_seconds"] = timings.wall;
  j["outputs"] = json::array();
  for (const auto& f : outputs.files) j["outputs"].push_back(f.string());
  return j.dump(2) + "\n";
}

void write_report(const std::filesystem::path& folder, const io::Case& c, const io::LoadedMesh& loaded,
                  const setup::CaseSetup& setup, const deform::MotionResult& result, const mesh::SolverQuality& solver,
                  const RunTimings& timings, const RunThreads& threads, RunOutputs& outputs,
                  const io::CheckpointInfo* resumed) {
  outputs.files.push_back(folder / "report.json");
  io::write_file_atomically(folder / "report.json",
                            deform_report(folder, c, loaded, setup, result, solver, timings, threads, outputs, resumed));
}

}  // namespace hotmesh::api
