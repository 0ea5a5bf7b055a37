// hotmesh app: outputs of a reconstructed curve: the undeformed and deformed curves sampled
// (CSV) and as B-splines (STEP, IGES), a picture with nodes and amplified deflections (SVG) and
// a summary of the fit (JSON). Every file is written atomically.
#include "fits/curve_outputs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "fits/cad_json.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/figure.hpp"
#include "fits/node_fit.hpp"

namespace hotmesh::app {

namespace {

using geometry::DeflectedCurve;
using geometry::Vec2;

/// 1, 2 or 5 times a power of ten, at most `value`.
double nice_below(double value) {
  const double decade = std::pow(10.0, std::floor(std::log10(value)));
  for (const double m : {5.0, 2.0, 1.0}) {
    if (m * decade <= value) return m * decade;
  }
  return decade;
}

double amplification_for(const setup::CurveRun& run, double size) {
  double largest = 0.0;
  for (const Vec2& d : run.nodes.deflections) largest = std::max(largest, geometry::norm(d));
  if (!(largest > 0.0) || !(size > 0.0)) return 1.0;
  return std::max(1.0, nice_below(0.1 * size / largest));
}

double curve_size(const DeflectedCurve& curve, const std::vector<double>& t) {
  Vec2 lo = curve.point(t.front(), 0.0);
  Vec2 hi = lo;
  for (const double s : t) {
    const Vec2 p = curve.point(s, 0.0);
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  return geometry::distance(lo, hi);
}

/// Picture coordinates: meridional curves with the axial coordinate z across and r up (as the
/// paper's Fig. 4), 2D curves as (x, y).
io::PlotPoint plot_point(const Vec2& p, bool meridional) {
  return meridional ? io::PlotPoint{p.y, p.x} : io::PlotPoint{p.x, p.y};
}

io::Figure picture(const setup::CurveRun& run, const std::vector<double>& t, double amplification) {
  const bool meridional = run.axis.has_value();
  const DeflectedCurve& curve = run.fit.curve;
  io::FigureLayout layout;
  layout.title = run.cad.empty() ? "Deflected boundary from FEM nodes"
                                 : "Deflected boundary: " + std::filesystem::path(run.cad).filename().string();
  const std::string unit = geometry::to_string(run.unit);
  layout.x_label = (meridional ? "z [" : "x [") + unit + "]";
  layout.y_label = (meridional ? "r [" : "y [") + unit + "]";
  io::Figure figure(layout);

  const io::Stroke undeformed{io::colors::grey, 2.0};
  const io::Stroke deformed{io::colors::red, 1.5};
  const io::Stroke arrows{io::colors::orange, 1.0};
  std::vector<io::PlotPoint> line;
  for (const double s : t) line.push_back(plot_point(curve.point(s, 0.0), meridional));
  figure.polyline(line, undeformed);
  line.clear();
  for (const double s : t) {
    const Vec2 r = curve.point(s, 0.0);
    line.push_back(plot_point(r + amplification * (curve.point(s, 1.0) - r), meridional));
  }
  figure.polyline(line, deformed);
  for (std::size_t j = 0; j < run.nodes.size(); ++j) {
    const Vec2 q = run.nodes.points[j];
    figure.arrow(plot_point(q, meridional), plot_point(q + amplification * run.nodes.deflections[j], meridional), arrows,
                 6.0);
    figure.marker(plot_point(q, meridional), io::colors::blue, 2.5);
  }
  for (const auto& rejected : run.fit.report.rejected_nodes) {
    figure.marker(plot_point(run.nodes.points[rejected.index], meridional), io::colors::black, 3.5);
  }
  const std::string times = fmt::format(" (deflection x {:g})", amplification);
  figure.legend(run.cad.empty() ? "undeformed curve through the FEM nodes" : "CAD curve r(t)", undeformed);
  figure.legend("FEM nodes", {io::colors::blue, 1.0}, true);
  figure.legend("FEM deflections" + times, arrows);
  figure.legend("reconstructed c(t)" + times, deformed);
  if (!run.fit.report.rejected_nodes.empty()) figure.legend("rejected nodes", {io::colors::black, 1.0}, true);
  return figure;
}

}  // namespace

std::vector<double> sample_parameters(const DeflectedCurve& curve, std::size_t samples) {
  std::vector<double> t;
  const double a = curve.first_parameter();
  const double b = curve.last_parameter();
  for (std::size_t i = 0; i <= samples; ++i) t.push_back(a + (b - a) * static_cast<double>(i) / static_cast<double>(samples));
  for (const auto& piece : curve.pieces()) t.push_back(piece.begin);
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

std::string curve_csv(const DeflectedCurve& curve, const std::vector<double>& t, double lambda, bool meridional) {
  std::string text = meridional ? "t,r,z\n" : "t,x,y\n";
  for (const double s : t) {
    const Vec2 p = curve.point(s, lambda);
    text += fmt::format("{:.15g},{:.15g},{:.15g}\n", s, p.x, p.y);
  }
  return text;
}

geometry::CadExport curve_export(const setup::CurveRun& run) {
  const DeflectedCurve& curve = run.fit.curve;
  geometry::CadExport content;
  content.unit = run.unit;
  const geometry::PlaneFrame frame = run.axis ? geometry::meridional_frame(*run.axis) : geometry::PlaneFrame{};
  content.curves.push_back({"undeformed", curve.undeformed(), frame});
  content.curves.push_back({"deformed", curve.stage(1.0), frame});
  return content;
}

double automatic_amplification(const setup::CurveRun& run) {
  const DeflectedCurve& curve = run.fit.curve;
  return amplification_for(run, curve_size(curve, sample_parameters(curve, 2000)));
}

nlohmann::json curve_summary(const setup::CurveRun& run, double amplification) {
  const geometry::ReconstructionReport& report = run.fit.report;
  nlohmann::json rejected = nlohmann::json::array();
  for (const auto& node : report.rejected_nodes) {
    nlohmann::json entry = dropped_node_json(node, run.nodes.ids, run.nodes.lines);
    entry["parameter"] = node.parameter;
    rejected.push_back(entry);
  }
  const nlohmann::json axis = run.axis ? axis_json(*run.axis) : nlohmann::json(nullptr);
  return {{"nodes", report.nodes},
          {"used_nodes", report.used_nodes},
          {"merged_duplicates", report.merged_duplicates},
          {"degree", report.degree},
          {"form", geometry::to_string(report.form)},
          {"frame", run.axis ? "rz" : "xy"},
          {"unit", geometry::to_string(run.unit)},
          {"parameter_range", {report.fem_first, report.fem_last}},
          {"curve_parameter_range", {report.curve_first, report.curve_last}},
          {"max_node_distance_to_cad", report.max_node_distance_to_cad},
          {"max_node_residual", report.max_node_residual},
          {"tolerance", report.tolerance},
          {"max_out_of_plane_deflection", report.max_out_of_plane_deflection},
          {"rejected_nodes", rejected},
          {"cad", run.cad.empty() ? nlohmann::json(nullptr) : nlohmann::json(run.cad)},
          {"faces", run.faces},
          {"axis", axis},
          {"amplification", amplification}};
}

std::string write_curve_outputs(const std::filesystem::path& folder, const setup::CurveRun& run,
                                const CurveOutputOptions& options) {
  // Everything is computed first, so a failure leaves no partial outputs behind.
  const DeflectedCurve& curve = run.fit.curve;
  const bool meridional = run.axis.has_value();
  const std::vector<double> t = sample_parameters(curve, std::max<std::size_t>(options.samples, 2));
  const geometry::CadExport content = curve_export(run);
  const double amplification =
      options.amplification > 0.0 ? options.amplification : amplification_for(run, curve_size(curve, t));
  const io::Figure figure = picture(run, t, amplification);
  nlohmann::json summary = curve_summary(run, amplification);
  summary["files"] = kCurveFiles;
  const std::string text = summary.dump(2) + "\n";
  const std::pair<const char*, std::string> files[] = {{"undeformed.csv", curve_csv(curve, t, 0.0, meridional)},
                                                       {"deformed.csv", curve_csv(curve, t, 1.0, meridional)},
                                                       {"curves.step", geometry::to_step(content)},
                                                       {"curves.igs", geometry::to_iges(content)}};
  for (const auto& [name, file] : files) io::write_file_atomically(folder / name, file);
  figure.save(folder / "plot.svg");
  io::write_file_atomically(folder / "summary.json", text);
  return text;
}

}  // namespace hotmesh::app
