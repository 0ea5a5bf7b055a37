// hotmesh serve: the geometry service's curves: deflected curves reconstructed through FEM
// nodes (section 4.2, eq. 21) on CAD faces' meridional curves, on CAD edges in the plane z = 0
// (2D walls) or without CAD, projection of points onto a stage of a curve, and the curves as
// STEP, IGES or CSV files.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "fits/cad_json.hpp"
#include "fits/curve_outputs.hpp"
#include "hotmesh/geometry/boundary_shapes.hpp"
#include "hotmesh/geometry/cad_export.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/geometry/reconstruction.hpp"
#include "hotmesh/io/deflection_csv.hpp"
#include "service/curve_json.hpp"
#include "service/service.hpp"
#include "service/service_state.hpp"

namespace hotmesh::app::serve {

Json store_curve(GeometryService::State& state, setup::CurveRun run, bool deflected, std::size_t samples, Json extra) {
  const std::string id = state.curves.next_id();
  const geometry::DeflectedCurve& curve = run.fit.curve;
  auto projector = std::make_unique<geometry::CurveProjector>(curve);
  std::unique_ptr<geometry::BoundaryShape> shape;
  if (run.axis) {
    shape = std::make_unique<geometry::RevolvedShape>(curve, *run.axis);
  } else {
    shape = std::make_unique<geometry::PlanarCurveShape>(curve);
  }

  const std::vector<double> t = sample_parameters(curve, samples);
  Json body = {{"curve", id},
               {"kind", deflected ? "reconstructed" : "meridional"},
               {"frame", run.axis ? "rz" : "xy"},
               {"unit", geometry::to_string(run.unit)},
               {"axis", run.axis ? axis_json(*run.axis) : Json(nullptr)},
               {"faces", run.faces},
               {"model", nullptr},
               {"undeformed", curve_json(curve.undeformed(), curve, t, 0.0)},
               {"deformed", nullptr},
               {"nodes", Json::array()},
               {"summary", nullptr},
               {"amplification", nullptr}};
  if (deflected) {
    const geometry::CurveProjector undeformed{geometry::DeflectedCurve(curve.undeformed())};
    const double amplification = automatic_amplification(run);
    body["deformed"] = curve_json(curve.stage(1.0), curve, t, 1.0);
    body["nodes"] = node_fits_json(run, undeformed);
    body["summary"] = curve_summary(run, amplification);
    body["amplification"] = amplification;
  }
  const std::string base = "/api/curves/" + id + "/download?format=";
  body["downloads"] = {{"step", base + "step"}, {"iges", base + "iges"}, {"csv", base + "csv"}};
  body.update(extra);
  std::string text = body.dump(-1, ' ', false, Json::error_handler_t::replace);
  // What a curve costs: its answer, and about as much again for the nodes, curves and samples.
  const std::size_t bytes = 2 * text.size();
  auto stored = std::make_shared<const StoredCurve>(StoredCurve{
      id, deflected, std::move(run), std::move(projector), std::move(shape), std::move(text), body["frame"]});
  state.curves.insert(std::move(stored), id, bytes);
  return body;
}

geometry::DeflectionSamples table_field(const Json& request, const ServiceLimits& limits) {
  const std::string csv = string_field(request, "csv");
  const std::string name = string_field(request, "csv_name", "csv");
  const auto lines = static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n'));
  const std::string limit = fmt::format("more than the limit of {} nodes (hotmesh serve --max-nodes)", limits.max_nodes);
  if (lines > 2 * limits.max_nodes + 1000) {
    throw ApiError::bad_request(fmt::format("csv: {} lines, {}", lines, limit));
  }
  geometry::DeflectionSamples samples;
  try {
    samples = io::parse_deflection_csv(csv, name);
  } catch (const InputError& e) {
    throw ApiError::bad_request(std::string("csv: ") + e.what());
  }
  if (samples.size() > limits.max_nodes) throw ApiError::bad_request(fmt::format("csv: {} nodes, {}", samples.size(), limit));
  return samples;
}

geometry::ReconstructionOptions reconstruction_field(const Json& request) {
  geometry::ReconstructionOptions options;
  options.degree = static_cast<int>(integer_field(request, "degree", 1, geometry::kMaxReconstructionDegree, 1));
  const std::string form = string_field(request, "form", "curve");
  const auto known_form = geometry::kDeflectionFormNames.parse(form);
  if (!known_form) {
    throw ApiError::bad_request(fmt::format("form: expected \"curve\" or \"displacement\", got \"{}\"", form));
  }
  options.form = *known_form;
  options.tolerance = number_field(request, "tolerance", 0.0, 1e300, 0.0);
  options.far_nodes = bool_field(request, "drop_far_nodes", false) ? geometry::FarNodePolicy::drop
                                                                     : geometry::FarNodePolicy::reject;
  return options;
}

Json GeometryService::create_curve(const Json& request) {
  refuse_unknown_keys(request, {"model", "faces", "edges", "axis", "csv", "csv_name", "degree", "form", "tolerance",
                                "drop_far_nodes", "samples", "unit"});
  const ServiceLimits& limits = state_->limits;
  const auto samples =
      static_cast<std::size_t>(integer_field(request, "samples", 2, static_cast<long long>(limits.max_samples), 400));
  const geometry::ReconstructionOptions options = reconstruction_field(request);
  const std::optional<geometry::Axis> axis = axis_field(request, "axis");
  const bool with_cad = request.contains("model") && !request["model"].is_null();
  for (const char* key : {"faces", "edges"}) {
    if (!with_cad && request.contains(key)) {
      throw ApiError::bad_request(fmt::format("{}: needs \"model\", the CAD model they belong to", key));
    }
  }
  if (request.contains("faces") && request.contains("edges")) {
    throw ApiError::bad_request("edges: give either \"faces\" (a surface of revolution) or \"edges\" (a 2D wall in "
                                "the plane z = 0), not both");
  }
  if (with_cad && request.contains("unit")) {
    throw ApiError::bad_request("unit: a CAD model's unit applies (load the model with another unit instead)");
  }

  std::optional<setup::CurveRun> run;
  Json extra = Json::object();
  if (with_cad && request.contains("edges")) {
    const auto model = state_->models.get(string_field(request, "model"), "model");
    const std::vector<int> edges = model_edges_field(request, "edges", *model, limits.max_faces);
    const geometry::DeflectionSamples table = table_field(request, limits);
    try {
      std::optional<geometry::PlanarCurve> curve;
      {
        std::lock_guard lock(model->mutex);
        curve.emplace(model->cad.planar_curve(edges));
      }
      run.emplace(setup::fit_on_plane_cad_curve(curve->curve, table, axis, options, model->cad.unit(), model->name));
      run->edges = curve->edges;
      extra = {{"model", model->id}, {"edges", curve->edges}, {"edge_breaks", curve->edge_breaks}};
    } catch (const InputError& e) {
      throw ApiError::unprocessable(e.what());
    }
  } else if (with_cad) {
    const auto model = state_->models.get(string_field(request, "model"), "model");
    const std::vector<int> faces = model_faces_field(request, "faces", *model, limits.max_faces);
    const geometry::DeflectionSamples table = table_field(request, limits);
    if (table.frame == geometry::SampleFrame::meridional && !axis) {
      throw ApiError::bad_request("axis: meridional (r, z) nodes need the axis their z is measured along");
    }
    try {
      setup::require_cad_frame(table);
      std::optional<geometry::MeridionalCurve> curve;
      {
        std::lock_guard lock(model->mutex);
        curve.emplace(model->cad.meridional_curve(faces, {.axis = axis}));
      }
      run.emplace(setup::fit_on_cad_curve(*curve, table, options, model->cad.unit(), model->name));
      extra = {{"model", model->id}, {"face_breaks", curve->face_breaks}};
    } catch (const InputError& e) {
      throw ApiError::unprocessable(e.what());
    }
  } else {
    const std::string unit_text = string_field(request, "unit", "m");
    const auto unit = geometry::parse_length_unit(unit_text);
    if (!unit) throw ApiError::bad_request(fmt::format("unit: unknown length unit '{}' (use m, mm, cm, um, in or ft)", unit_text));
    const geometry::DeflectionSamples table = table_field(request, limits);
    try {
      run.emplace(setup::fit_without_cad(table, axis, options, *unit, "\"axis\""));
    } catch (const InputError& e) {
      throw ApiError::unprocessable(e.what());
    }
  }
  return store_curve(*state_, std::move(*run), true, samples, std::move(extra));
}

std::string GeometryService::curve(std::string_view id) const { return state_->curves.get(id, "curve")->body; }

void GeometryService::delete_curve(std::string_view id) { state_->curves.erase(id, "curve"); }

Json GeometryService::project(std::string_view curve_id, const Json& request) const {
  refuse_unknown_keys(request, {"points", "lambda"});
  const auto stored = state_->curves.get(curve_id, "curve");
  const double lambda = number_field(request, "lambda", 0.0, 1.0, 1.0);
  const auto it = request.find("points");
  const std::string expected = "points: expected an array of points, each [a, b] in the curve's plane or [x, y, z]";
  if (it == request.end() || !it->is_array() || it->empty()) throw ApiError::bad_request(expected);
  if (it->size() > state_->limits.max_points) {
    throw ApiError::bad_request(fmt::format("points: {} points, more than the limit of {}", it->size(),
                                            state_->limits.max_points));
  }
  const std::size_t dimension = it->front().is_array() ? it->front().size() : 0;
  if (dimension != 2 && dimension != 3) throw ApiError::bad_request(expected);
  Json projections = Json::array();
  for (std::size_t i = 0; i < it->size(); ++i) {
    const Json& p = (*it)[i];
    const bool numbers = p.is_array() && p.size() == dimension &&
                         std::all_of(p.begin(), p.end(), [](const Json& x) { return x.is_number(); });
    if (!numbers) throw ApiError::bad_request(fmt::format("points[{}]: expected {} numbers like points[0]", i, dimension));
    std::vector<double> x;
    for (const Json& value : p) x.push_back(value.get<double>());
    if (!std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); })) {
      throw ApiError::bad_request(fmt::format("points[{}]: the numbers must be finite", i));
    }
    if (dimension == 2) {
      const geometry::CurveProjection q = stored->projector->project({x[0], x[1]}, lambda);
      projections.push_back({{"point", {q.point.x, q.point.y}},
                             {"normal", {q.normal.x, q.normal.y}},
                             {"tangent", {q.tangent.x, q.tangent.y}},
                             {"parameter", q.parameter},
                             {"distance", q.distance}});
    } else {
      const geometry::ShapePoint q = stored->shape->project({x[0], x[1], x[2]}, lambda);
      projections.push_back({{"point", vec3_json(q.point)},
                             {"normal", vec3_json(q.normal)},
                             {"parameter", q.parameter.t},
                             {"distance", q.distance}});
    }
  }
  return {{"curve", stored->id}, {"lambda", lambda}, {"frame", stored->frame}, {"projections", projections}};
}

Download GeometryService::download(std::string_view curve_id, std::string_view format) const {
  const auto stored = state_->curves.get(curve_id, "curve");
  const setup::CurveRun& run = stored->run;
  if (format == "step") return {geometry::to_step(curve_export(run)), "model/step", stored->id + "-curves.step"};
  if (format == "iges") return {geometry::to_iges(curve_export(run)), "model/iges", stored->id + "-curves.igs"};
  if (format == "csv") {
    const geometry::DeflectedCurve& curve = run.fit.curve;
    const std::string stage = stored->deflected ? "deformed" : "undeformed";
    return {curve_csv(curve, sample_parameters(curve, 2000), stored->deflected ? 1.0 : 0.0, run.axis.has_value()),
            "text/csv; charset=utf-8", stored->id + "-" + stage + ".csv"};
  }
  throw ApiError::bad_request(fmt::format("format: expected step, iges or csv, got '{}'", format));
}

}  // namespace hotmesh::app::serve
