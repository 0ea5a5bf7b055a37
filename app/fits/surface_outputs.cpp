// hotmesh app: outputs of deflection fields on CAD faces: the deformed faces (STEP, IGES), the
// nodes and faces for ParaView (.vtp), the residuals over (t, s) (PNG) and a summary (JSON).
// Every file is written atomically.
#include "fits/surface_outputs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "hotmesh/io/atomic_file.hpp"
#include "fits/node_fit.hpp"

namespace hotmesh::app {

namespace {

using geometry::BSplineSurface;
using geometry::ParameterRectangle;
using geometry::Vec3;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const char* method_name(geometry::SurfaceFitMethod method) {
  return method == geometry::SurfaceFitMethod::interpolation ? "interpolation" : "least_squares";
}

/// The parameter at fraction f of [a, b].
double lerp(double a, double b, double f) { return a + (b - a) * f; }

// The residual picture: one panel per face, kPitch world units apart in rows of `columns`.
constexpr double kPitch = 1.6;

/// A face's (t, s) rectangle in the picture, drawn with the proportions of the face itself
/// (geometry::face_aspect): the longer side one unit, the shorter at least a quarter. Its lower
/// left corner is at the panel's origin.
struct Panel {
  ParameterRectangle r;
  io::PlotPoint origin;
  double width = 1.0;
  double height = 1.0;

  Panel(const BSplineSurface& face, std::size_t index, std::size_t columns)
      : r(face.domain()),
        origin{kPitch * static_cast<double>(index % columns), -kPitch * static_cast<double>(index / columns)} {
    const double aspect = geometry::face_aspect(face);  // width over height
    width = std::max(0.25, std::min(1.0, aspect));
    height = std::max(0.25, std::min(1.0, 1.0 / aspect));
  }
  io::PlotPoint at(double t, double s) const {
    return {origin.x + width * (t - r.u_first) / (r.u_last - r.u_first),
            origin.y + height * (s - r.v_first) / (r.v_last - r.v_first)};
  }
};

}  // namespace

std::vector<double> placement_residuals(const setup::SurfaceRun& run) {
  std::vector<double> residuals;
  residuals.reserve(run.fit.placements.size());
  for (const geometry::NodePlacement& p : run.fit.placements) {
    residuals.push_back(distance(run.fit.fields[p.face].point(p.t, p.s), run.samples.deflections[p.node]));
  }
  return residuals;
}

std::vector<geometry::DeformedFace> deformed_faces(const setup::SurfaceRun& run, const geometry::DeformedFaceOptions& options) {
  std::vector<geometry::DeformedFace> deformed;
  for (std::size_t f = 0; f < run.faces.size(); ++f) {
    deformed.push_back(geometry::deformed_face(run.faces[f].surface, run.fit.fields[f], options));
  }
  return deformed;
}

geometry::CadExport surface_export(const setup::SurfaceRun& run, std::span<const geometry::DeformedFace> deformed) {
  geometry::CadExport content;
  content.unit = run.unit;
  for (std::size_t f = 0; f < run.faces.size(); ++f) {
    content.surfaces.push_back({"face " + std::to_string(run.faces[f].id), deformed[f].surface});
  }
  return content;
}

io::PolyData node_points(const setup::SurfaceRun& run, std::span<const double> residuals) {
  const geometry::DeflectionSamples& samples = run.samples;
  io::PolyData data;
  std::vector<double> deflection, t, s, distance, residual;
  std::vector<std::int32_t> face;
  std::vector<std::uint8_t> rejected;
  std::vector<std::int64_t> line, id;
  const auto add = [&](std::size_t node) {
    data.vertices.push_back({static_cast<std::int64_t>(data.points.size())});
    data.points.push_back(samples.points[node]);
    const Vec3& d = samples.deflections[node];
    deflection.insert(deflection.end(), {d.x, d.y, d.z});
    line.push_back(node < samples.lines.size() ? static_cast<std::int64_t>(samples.lines[node]) : 0);
    if (!samples.ids.empty()) id.push_back(samples.ids[node]);
  };
  for (std::size_t k = 0; k < run.fit.placements.size(); ++k) {
    const geometry::NodePlacement& p = run.fit.placements[k];
    add(p.node);
    face.push_back(run.faces[p.face].id);
    t.push_back(p.t);
    s.push_back(p.s);
    distance.push_back(p.distance);
    residual.push_back(residuals[k]);
    rejected.push_back(0);
  }
  for (const geometry::NodeDistance& node : run.fit.report.rejected_nodes) {
    add(node.index);
    face.push_back(0);
    t.push_back(kNaN);
    s.push_back(kNaN);
    distance.push_back(node.distance);
    residual.push_back(kNaN);
    rejected.push_back(1);
  }
  data.point_data.push_back({"deflection", 3, std::move(deflection)});
  data.point_data.push_back({"face", 1, std::move(face)});
  data.point_data.push_back({"t", 1, std::move(t)});
  data.point_data.push_back({"s", 1, std::move(s)});
  data.point_data.push_back({"distance", 1, std::move(distance)});
  data.point_data.push_back({"residual", 1, std::move(residual)});
  data.point_data.push_back({"rejected", 1, std::move(rejected)});
  data.point_data.push_back({"line", 1, std::move(line)});
  if (!samples.ids.empty()) data.point_data.push_back({"id", 1, std::move(id)});
  return data;
}

io::PolyData face_grids(const setup::SurfaceRun& run, std::size_t samples) {
  const std::size_t n = std::max<std::size_t>(samples, 1);
  io::PolyData data;
  std::vector<double> deflection, magnitude, t, s;
  std::vector<std::int32_t> face;
  for (std::size_t f = 0; f < run.faces.size(); ++f) {
    const BSplineSurface& surface = run.faces[f].surface;
    const BSplineSurface& field = run.fit.fields[f];
    const ParameterRectangle r = surface.domain();
    const auto base = static_cast<std::int64_t>(data.points.size());
    for (std::size_t i = 0; i <= n; ++i) {
      for (std::size_t j = 0; j <= n; ++j) {
        const double u = lerp(r.u_first, r.u_last, static_cast<double>(i) / static_cast<double>(n));
        const double v = lerp(r.v_first, r.v_last, static_cast<double>(j) / static_cast<double>(n));
        const Vec3 d = field.point(u, v);
        data.points.push_back(surface.point(u, v) + d);
        deflection.insert(deflection.end(), {d.x, d.y, d.z});
        magnitude.push_back(norm(d));
        t.push_back(u);
        s.push_back(v);
        face.push_back(run.faces[f].id);
      }
    }
    const auto row = static_cast<std::int64_t>(n + 1);
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(n); ++i) {
      for (std::int64_t j = 0; j < static_cast<std::int64_t>(n); ++j) {
        const std::int64_t a = base + i * row + j;  // (t_i, s_j); t grows along +row, s along +1
        data.polygons.push_back({a, a + row, a + row + 1});
        data.polygons.push_back({a, a + row + 1, a + 1});
      }
    }
  }
  data.point_data.push_back({"deflection", 3, std::move(deflection)});
  data.point_data.push_back({"deflection_magnitude", 1, std::move(magnitude)});
  data.point_data.push_back({"face", 1, std::move(face)});
  data.point_data.push_back({"t", 1, std::move(t)});
  data.point_data.push_back({"s", 1, std::move(s)});
  return data;
}

io::Figure residual_picture(const setup::SurfaceRun& run, std::span<const double> residuals) {
  const std::size_t panels = run.faces.size();
  const auto columns = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(panels))));
  const std::size_t rows = (panels + columns - 1) / columns;
  io::FigureLayout layout;
  layout.width = std::max(900, 110 + 420 * static_cast<int>(columns));
  layout.height = 150 + 420 * static_cast<int>(rows);
  layout.axes = false;
  layout.title = "Residuals |d(t, s) - delta| at the FEM nodes: " + std::filesystem::path(run.cad).filename().string();
  io::Figure figure(layout);
  const double largest = residuals.empty() ? 0.0 : *std::max_element(residuals.begin(), residuals.end());
  const auto shade = [&](double r) { return io::colormap(largest > 0.0 ? r / largest : 0.0); };
  figure.color_bar(fmt::format("residual [{}]", geometry::to_string(run.unit)), 0.0, largest);

  // The placements of each face, least residual first so the worst are drawn on top.
  std::vector<std::vector<std::size_t>> on_face(panels);
  for (std::size_t k = 0; k < run.fit.placements.size(); ++k) on_face[run.fit.placements[k].face].push_back(k);
  const io::Stroke frame{io::colors::black, 1.0};
  const io::Stroke knots{{0.8, 0.8, 0.8}, 0.75};
  double top = 0.0;  // of the first row's panels
  for (std::size_t f = 0; f < panels; ++f) {
    const Panel panel(run.faces[f].surface, f, columns);
    if (f < columns) top = std::max(top, panel.height);
    const ParameterRectangle& r = panel.r;
    const BSplineSurface& field = run.fit.fields[f];
    const auto at = [&](double t, double s) { return panel.at(t, s); };
    for (const double t : field.u_breakpoints()) {
      const std::array<io::PlotPoint, 2> line{at(t, r.v_first), at(t, r.v_last)};
      figure.polyline(line, knots);
    }
    for (const double s : field.v_breakpoints()) {
      const std::array<io::PlotPoint, 2> line{at(r.u_first, s), at(r.u_last, s)};
      figure.polyline(line, knots);
    }
    const std::array<io::PlotPoint, 4> corners{at(r.u_first, r.v_first), at(r.u_last, r.v_first),
                                               at(r.u_last, r.v_last), at(r.u_first, r.v_last)};
    figure.polyline(corners, frame, true);

    std::vector<std::size_t>& order = on_face[f];
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return residuals[a] < residuals[b]; });
    for (const std::size_t k : order) {
      const geometry::NodePlacement& p = run.fit.placements[k];
      if (k == order.back()) figure.marker(at(p.t, p.s), io::colors::black, 7.0);  // the worst, ringed
      figure.marker(at(p.t, p.s), shade(residuals[k]), 4.5);
    }

    const geometry::FaceFitReport& report = run.fit.report.faces[f];
    const io::PlotPoint above{panel.origin.x, panel.origin.y + panel.height};
    figure.text(above, fmt::format("face {}: max {:.3g}", run.faces[f].id, report.fit.max_residual), 15.0,
                io::colors::black, {0.0, 44.0});
    if (!order.empty()) {
      figure.text(above, "at " + run.samples.label(run.fit.placements[order.back()].node), 12.0, io::colors::black,
                  {0.0, 26.0});
    }
    figure.text(above,
                fmt::format("{} nodes, {}, {} x {} poles", report.nodes, method_name(report.fit.method),
                            report.fit.u_poles, report.fit.v_poles),
                12.0, io::colors::black, {0.0, 8.0});
    figure.text(panel.origin, fmt::format("t across: {:.6g} to {:.6g}", r.u_first, r.u_last), 12.0, io::colors::black,
                {0.0, -18.0});
    figure.text(panel.origin, fmt::format("s up: {:.6g} to {:.6g}", r.v_first, r.v_last), 12.0, io::colors::black,
                {0.0, -34.0});
  }
  // Room for the labels: the layout gives at least 280 pixels per world unit, so 0.22 above is 62
  // pixels or more, and the last column's labels have 1.1 units (308 pixels) from its left edge.
  const double right = kPitch * static_cast<double>(columns - 1) + 1.0;
  const double bottom = -kPitch * static_cast<double>(rows - 1);
  figure.set_view(-0.1, right + 0.1, bottom - 0.2, top + 0.22);
  return figure;
}

nlohmann::json surface_summary(const setup::SurfaceRun& run, std::span<const geometry::DeformedFace> deformed) {
  const geometry::SurfaceReconstructionReport& report = run.fit.report;
  nlohmann::json rejected = nlohmann::json::array();
  for (const auto& node : report.rejected_nodes) rejected.push_back(dropped_node_json(node, run.samples.ids, run.samples.lines));
  nlohmann::json faces = nlohmann::json::array();
  std::vector<int> ids;
  for (std::size_t f = 0; f < run.faces.size(); ++f) {
    const geometry::FaceFitReport& fit = report.faces[f];
    const BSplineSurface& surface = run.faces[f].surface;
    const BSplineSurface& exported = deformed[f].surface;
    ids.push_back(run.faces[f].id);
    faces.push_back({{"id", run.faces[f].id},
                     {"name", run.info[f].name},
                     {"kind", geometry::to_string(run.info[f].kind)},
                     {"rational", surface.is_rational()},
                     {"parameter_range", {{"t", {surface.u_first(), surface.u_last()}},
                                          {"s", {surface.v_first(), surface.v_last()}}}},
                     {"nodes", fit.nodes},
                     {"method", method_name(fit.fit.method)},
                     {"poles", {fit.fit.u_poles, fit.fit.v_poles}},
                     {"max_residual", fit.fit.max_residual},
                     {"rms_residual", fit.fit.rms_residual},
                     {"exact", deformed[f].exact},
                     {"max_deviation", deformed[f].max_deviation},
                     {"deviation_checks", deformed[f].check_points},
                     {"export_degree", {exported.u_degree(), exported.v_degree()}},
                     {"export_poles", {exported.u_count(), exported.v_count()}}});
  }
  return {{"inputs", {{"cad", run.cad}, {"fem", run.samples.source}, {"faces", ids}, {"unit", geometry::to_string(run.unit)}}},
          {"degree", report.degree},
          {"tolerance", report.tolerance},
          {"nodes", report.nodes},
          {"used_nodes", report.used_nodes},
          {"rejected_nodes", rejected},
          {"faces", faces},
          {"max_edge_gap", report.max_edge_gap},
          {"shared_edges", report.shared_edges},
          {"joined_edges", report.joined_edges},
          {"max_node_distance_to_cad", report.max_node_distance_to_cad},
          {"max_node_residual", report.max_node_residual}};
}

nlohmann::json write_surface_outputs(const std::filesystem::path& folder, const setup::SurfaceRun& run,
                                     const SurfaceOutputOptions& options) {
  // Everything is computed first, so a failure leaves no partial outputs behind.
  const std::vector<geometry::DeformedFace> deformed = deformed_faces(run, options.deformed);
  const geometry::CadExport content = surface_export(run, deformed);
  const std::vector<double> residuals = placement_residuals(run);
  const io::PolyData nodes = node_points(run, residuals);
  const io::PolyData faces = face_grids(run, options.samples);
  const io::Figure figure = residual_picture(run, residuals);
  nlohmann::json summary = surface_summary(run, deformed);
  summary["files"] = kSurfaceFiles;
  const std::string text = summary.dump(2) + "\n";
  const std::string step = geometry::to_step(content);
  const std::string iges = geometry::to_iges(content);

  io::write_file_atomically(folder / "deformed.step", step);
  io::write_file_atomically(folder / "deformed.iges", iges);
  io::write_vtp(folder / "nodes.vtp", nodes);
  io::write_vtp(folder / "faces.vtp", faces);
  figure.save(folder / "residuals.png");
  io::write_file_atomically(folder / "summary.json", text);
  return summary;
}

}  // namespace hotmesh::app
