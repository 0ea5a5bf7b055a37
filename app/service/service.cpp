// hotmesh serve: the geometry service's CAD side: health, files below the root, loading CAD
// models (upload or root), listing their faces and edges, how faces are taken (as a surface of
// revolution or as surfaces, faces_mode.hpp) and meridional curves of faces (eq. 20).
#include "service/service.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <string_view>
#include <utility>

#include "fits/cad_json.hpp"
#include "hotmesh/setup/faces_mode.hpp"
#include "hotmesh/core/input_error.hpp"
#include "service/service_state.hpp"

namespace hotmesh::app::serve {

namespace {

const std::vector<std::string> kCadExtensions{".step", ".stp", ".iges", ".igs"};
const std::vector<std::string> kTableExtensions{".csv"};

geometry::LengthUnit unit_value(std::string_view text) {
  const auto unit = geometry::parse_length_unit(text);
  if (!unit) throw ApiError::bad_request(fmt::format("unit: unknown length unit '{}' (use m, mm, cm, um, in or ft)", text));
  return *unit;
}

void require_cad_extension(std::string_view name, const char* key) {
  const std::string ext = lower_extension(name);
  if (std::find(kCadExtensions.begin(), kCadExtensions.end(), ext) == kCadExtensions.end()) {
    throw ApiError::unsupported_type(
        fmt::format("{}: '{}' is not a CAD file: expected .step, .stp, .iges or .igs", key, name));
  }
}

Json model_summary(const StoredModel& model) {
  return {{"model", model.id},
          {"name", model.name},
          {"source", model.source},
          {"unit", geometry::to_string(model.cad.unit())},
          {"face_count", model.cad.faces().size()},
          {"edge_count", model.cad.edges().size()}};
}

/// The ids of request[key], each at most `count` (the model's faces or edges, as `word` says).
std::vector<int> ids_field(const Json& request, const char* key, std::size_t count, std::string_view word,
                           std::size_t max_ids) {
  std::vector<int> ids = face_list_field(request, key, max_ids, word);
  for (const int id : ids) {
    if (static_cast<std::size_t>(id) > count) {
      throw ApiError::bad_request(fmt::format("{}: the model has {} {}s; there is no {} {}", key, count, word, word, id));
    }
  }
  return ids;
}

}  // namespace

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  if (from.empty()) return text;
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

std::vector<int> model_faces_field(const Json& request, const char* key, const StoredModel& model, std::size_t max_faces) {
  return ids_field(request, key, model.cad.faces().size(), "face", max_faces);
}

std::vector<int> model_edges_field(const Json& request, const char* key, const StoredModel& model, std::size_t max_edges) {
  return ids_field(request, key, model.cad.edges().size(), "edge", max_edges);
}

GeometryService::GeometryService(const std::optional<std::filesystem::path>& root, ServiceLimits limits)
    : state_(std::make_unique<State>(root, limits)) {}

GeometryService::~GeometryService() = default;

const ServiceLimits& GeometryService::limits() const { return state_->limits; }

Json GeometryService::health() const {
  const ServiceLimits& l = state_->limits;
  return {{"status", "ok"},
          {"version", HOTMESH_VERSION},
          {"root", state_->root.has_value()},
          {"limits",
           {{"max_body_bytes", l.max_body_bytes},
            {"max_nodes", l.max_nodes},
            {"max_points", l.max_points},
            {"max_samples", l.max_samples},
            {"max_models", l.max_models},
            {"max_curves", l.max_curves},
            {"max_surfaces", l.max_surfaces},
            {"max_grid", l.max_grid},
            {"max_grid_points", l.max_grid_points}}},
          {"kept",
           {{"models", state_->models.size()},
            {"curves", state_->curves.size()},
            {"curve_bytes", state_->curves.bytes()},
            {"max_curve_bytes", l.max_curve_bytes},
            {"surfaces", state_->surfaces.size()},
            {"surface_bytes", state_->surfaces.bytes()},
            {"max_surface_bytes", l.max_surface_bytes}}}};
}

Json GeometryService::files() const {
  Json files = Json::array();
  if (state_->root) {
    std::vector<std::string> extensions = kCadExtensions;
    extensions.insert(extensions.end(), kTableExtensions.begin(), kTableExtensions.end());
    for (const auto& entry : state_->root->list(extensions, 1000, 6)) {
      const std::string ext = lower_extension(entry.path);
      const bool cad = std::find(kCadExtensions.begin(), kCadExtensions.end(), ext) != kCadExtensions.end();
      files.push_back({{"path", entry.path}, {"bytes", entry.bytes}, {"kind", cad ? "cad" : "table"}});
    }
  }
  return {{"root", state_->root.has_value()}, {"files", files}};
}

namespace {

/// Reads a CAD file that the service stored in its private folder, and removes the copy (the
/// model holds the shape); messages name `name`, the client's name for it, not the copy.
std::shared_ptr<StoredModel> read_model(GeometryService::State& state, PrivateFile copy, std::string name,
                                        std::string source, geometry::LengthUnit unit) {
  const PrivateFile file = std::move(copy);
  std::optional<geometry::CadModel> cad;
  try {
    check_cad_in_child(state.limits.cad_check, file.path(), unit);
    cad.emplace(geometry::CadModel::read(file.path(), {.unit = unit}));
  } catch (const InputError& e) {
    throw ApiError::unprocessable(replaced(e.what(), file.path().string(), name));
  }
  auto model = std::shared_ptr<StoredModel>(
      new StoredModel{state.models.next_id(), std::move(name), std::move(source), std::move(*cad), {}, {}, {}});
  model->faces = faces_json(model->cad);
  model->edges = edges_json(model->cad);
  state.models.insert(model, model->id);
  return model;
}

Json model_answer(const StoredModel& model) {
  Json answer = model_summary(model);
  answer["faces"] = model.faces;
  answer["edges"] = model.edges;
  return answer;
}

}  // namespace

Json GeometryService::load_path(const Json& request) {
  refuse_unknown_keys(request, {"path", "unit"});
  const std::string path = string_field(request, "path");
  const geometry::LengthUnit unit = unit_value(string_field(request, "unit", "m"));
  if (!state_->root) {
    throw ApiError::forbidden("loading by path is off: start 'hotmesh serve --root DIR' to allow files below DIR, "
                              "or upload the file (multipart/form-data, field 'file')");
  }
  const std::string content = state_->root->read(path, state_->limits.max_body_bytes);  // confined first
  require_cad_extension(path, "path");
  return model_answer(*read_model(*state_, state_->uploads.write(lower_extension(path), content), path, "root", unit));
}

Json GeometryService::load_upload(std::string_view filename, std::string_view content, std::string_view unit_text) {
  const geometry::LengthUnit unit = unit_value(unit_text);
  if (filename.empty()) throw ApiError::bad_request("file: the upload has no file name (its extension gives the format)");
  require_cad_extension(filename, "file");
  if (content.empty()) throw ApiError::bad_request(fmt::format("file: '{}' is empty", filename));
  PrivateFile copy = state_->uploads.write(lower_extension(filename), content);
  const std::string name = std::filesystem::path(std::string(filename)).filename().string();
  return model_answer(*read_model(*state_, std::move(copy), name, "upload", unit));
}

Json GeometryService::models() const {
  Json list = Json::array();
  for (const auto& model : state_->models.all()) list.push_back(model_summary(*model));
  return {{"models", list}};
}

Json GeometryService::model(std::string_view id) const { return model_answer(*state_->models.get(id, "model")); }

Json GeometryService::faces(std::string_view id) const {
  const auto model = state_->models.get(id, "model");
  return {{"model", model->id}, {"faces", model->faces}};
}

void GeometryService::delete_model(std::string_view id) { state_->models.erase(id, "model"); }

Json GeometryService::meridional(std::string_view model_id, const Json& request) {
  refuse_unknown_keys(request, {"faces", "axis", "samples"});
  const auto model = state_->models.get(model_id, "model");
  const std::vector<int> faces = model_faces_field(request, "faces", *model, state_->limits.max_faces);
  const std::optional<geometry::Axis> axis = axis_field(request, "axis");
  const auto samples = static_cast<std::size_t>(
      integer_field(request, "samples", 2, static_cast<long long>(state_->limits.max_samples), 400));
  std::optional<geometry::MeridionalCurve> curve;
  try {
    std::lock_guard lock(model->mutex);
    curve.emplace(model->cad.meridional_curve(faces, {.axis = axis}));
  } catch (const InputError& e) {
    throw ApiError::unprocessable(e.what());
  }
  setup::CurveRun run{{geometry::DeflectedCurve(curve->curve), {}}, {}, curve->axis, model->cad.unit(), curve->faces, model->name};
  Json extra = {{"model", model->id}, {"face_breaks", curve->face_breaks}, {"tolerance", curve->tolerance}};
  return store_curve(*state_, std::move(run), false, samples, std::move(extra));
}

Json GeometryService::faces_mode(std::string_view model_id, const Json& request) {
  refuse_unknown_keys(request, {"faces", "axis", "mode"});
  const auto model = state_->models.get(model_id, "model");
  const std::vector<int> faces = model_faces_field(request, "faces", *model, state_->limits.max_faces);
  const std::optional<geometry::Axis> axis = axis_field(request, "axis");
  const std::string asked_text = string_field(request, "mode", "auto");
  const auto asked = io::kWallModeNames.parse(asked_text);
  if (!asked) {
    throw ApiError::bad_request(
        fmt::format("mode: expected \"auto\", \"meridional\" or \"surface\", got \"{}\"", asked_text));
  }
  std::optional<setup::FacesMode> chosen;
  try {
    std::lock_guard lock(model->mutex);
    chosen.emplace(setup::choose_faces_mode(model->cad, faces, axis, *asked));
  } catch (const InputError& e) {  // meridional asked, and the faces turn about no one axis
    throw ApiError::unprocessable("mode meridional: " + replaced(e.what(), model->cad.path().string(), model->name));
  }
  const bool meridional = chosen->mode == io::WallMode::meridional;
  return {{"model", model->id},
          {"faces", faces},
          {"mode", std::string(io::kWallModeNames.name(chosen->mode))},
          {"axis", meridional ? axis_json(chosen->profiles.front().axis) : Json(nullptr)},
          {"profiles", chosen->profiles.size()},
          {"reason", chosen->reason.empty() ? Json(nullptr) : Json(chosen->reason)}};
}

}  // namespace hotmesh::app::serve
