// hotmesh serve: the geometry service's surfaces: the deflection field d(t, s) of CAD faces of
// any shape reconstructed through FEM nodes (section 4.2 on B-spline surfaces, issue 23), the
// same run as `hotmesh surface` (face_fit.hpp, surface_outputs.hpp), kept and answered as JSON;
// the deformed faces S + d as STEP or IGES files.
#include <fmt/format.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "hotmesh/geometry/cad_export.hpp"
#include "hotmesh/core/input_error.hpp"
#include "service/service.hpp"
#include "service/service_state.hpp"
#include "service/surface_json.hpp"
#include "fits/surface_outputs.hpp"

namespace hotmesh::app::serve {

namespace {

/// Grid points per direction of each face: "grid", bounded so that all faces together stay
/// within the limit.
std::size_t grid_field(const Json& request, std::size_t faces, const ServiceLimits& limits) {
  const auto n = static_cast<std::size_t>(integer_field(request, "grid", 2, static_cast<long long>(limits.max_grid), 24));
  if (n * n * faces > limits.max_grid_points) {
    throw ApiError::bad_request(fmt::format("grid: {} x {} points on each of {} faces is more than the limit of {} "
                                            "points in one answer: ask for a coarser grid or fewer faces",
                                            n, n, faces, limits.max_grid_points));
  }
  return n;
}

/// The faces of the model, read under its lock (a CadModel is for one thread at a time); the
/// run names the model as the client knows it.
setup::SurfaceRun faces_of(StoredModel& model, const std::vector<int>& ids) {
  std::lock_guard lock(model.mutex);
  try {
    setup::SurfaceRun run = setup::cad_faces_of(model.cad, ids);
    run.cad = model.name;
    return run;
  } catch (const InputError& e) {
    throw ApiError::unprocessable("faces: " + replaced(e.what(), model.cad.path().string(), model.name));
  }
}

}  // namespace

Json GeometryService::create_surface(const Json& request) {
  refuse_unknown_keys(request, {"model", "faces", "csv", "csv_name", "degree", "tolerance", "drop_far_nodes", "grid"});
  const ServiceLimits& limits = state_->limits;
  const auto model = state_->models.get(string_field(request, "model"), "model");
  const std::vector<int> ids = model_faces_field(request, "faces", *model, limits.max_faces);
  const std::size_t grid = grid_field(request, ids.size(), limits);
  const geometry::ReconstructionOptions options = reconstruction_field(request);
  geometry::DeflectionSamples table = table_field(request, limits);

  setup::SurfaceRun run = faces_of(*model, ids);
  try {
    setup::fit_deflections(run, std::move(table), options);
  } catch (const InputError& e) {
    // The table's faults (not cartesian, nodes far from the faces, too few nodes on a face),
    // in the words of `hotmesh surface`.
    throw ApiError::unprocessable(std::string("csv: ") + e.what());
  }
  std::vector<geometry::DeformedFace> deformed = deformed_faces(run, SurfaceOutputOptions{}.deformed);

  const std::string id = state_->surfaces.next_id();
  Json faces = Json::array();
  for (std::size_t f = 0; f < run.faces.size(); ++f) faces.push_back(face_grid_json(run, f, grid));
  const std::string base = "/api/surfaces/" + id + "/download?format=";
  Json body = {{"surface", id},
               {"model", model->id},
               {"unit", geometry::to_string(run.unit)},
               {"summary", surface_summary(run, deformed)},
               {"max_edge_gap", run.fit.report.max_edge_gap},
               {"nodes", placements_json(run, placement_residuals(run))},
               {"left_out", left_out_json(run)},
               {"faces", faces},
               {"downloads", {{"step", base + "step"}, {"iges", base + "iges"}}}};
  std::string text = body.dump(-1, ' ', false, Json::error_handler_t::replace);
  // What a surface costs: its answer, and about as much again for the table, faces and fields.
  const std::size_t bytes = 2 * text.size();
  auto stored = std::make_shared<const StoredSurface>(StoredSurface{id, std::move(run), std::move(deformed), std::move(text)});
  state_->surfaces.insert(std::move(stored), id, bytes);
  return body;
}

std::string GeometryService::surface(std::string_view id) const { return state_->surfaces.get(id, "surface")->body; }

void GeometryService::delete_surface(std::string_view id) { state_->surfaces.erase(id, "surface"); }

Download GeometryService::surface_download(std::string_view surface_id, std::string_view format) const {
  const auto stored = state_->surfaces.get(surface_id, "surface");
  const geometry::CadExport content = surface_export(stored->run, stored->deformed);
  if (format == "step") return {geometry::to_step(content), "model/step", stored->id + "-deformed.step"};
  if (format == "iges") return {geometry::to_iges(content), "model/iges", stored->id + "-deformed.igs"};
  throw ApiError::bad_request(fmt::format("format: expected step or iges, got '{}'", format));
}

}  // namespace hotmesh::app::serve
