// hotmesh serve: deflection fields on CAD faces as JSON (see surface_json.hpp).
#include "service/surface_json.hpp"

#include <vector>

#include "fits/cad_json.hpp"

namespace hotmesh::app::serve {

namespace {

/// The fields every node entry has: where it is in the table and what the FEM gave.
Json node_json(const setup::SurfaceRun& run, std::size_t node) {
  const geometry::DeflectionSamples& samples = run.samples;
  return {{"index", node},
          {"label", samples.label(node)},
          {"id", node < samples.ids.size() ? Json(samples.ids[node]) : Json(nullptr)},
          {"line", node < samples.lines.size() ? Json(samples.lines[node]) : Json(nullptr)},
          {"point", vec3_json(samples.points[node])},
          {"deflection", vec3_json(samples.deflections[node])}};
}

/// n parameters evenly from a to b, both ends included.
std::vector<double> evenly(double a, double b, std::size_t n) {
  std::vector<double> values;
  for (std::size_t i = 0; i < n; ++i) values.push_back(a + (b - a) * static_cast<double>(i) / static_cast<double>(n - 1));
  return values;
}

}  // namespace

Json placements_json(const setup::SurfaceRun& run, std::span<const double> residuals) {
  Json list = Json::array();
  for (std::size_t k = 0; k < run.fit.placements.size(); ++k) {
    const geometry::NodePlacement& p = run.fit.placements[k];
    Json entry = node_json(run, p.node);
    entry["face"] = run.faces[p.face].id;
    entry["t"] = p.t;
    entry["s"] = p.s;
    entry["distance"] = p.distance;
    entry["residual"] = residuals[k];
    list.push_back(std::move(entry));
  }
  return list;
}

Json left_out_json(const setup::SurfaceRun& run) {
  Json list = Json::array();
  for (const geometry::NodeDistance& node : run.fit.report.rejected_nodes) {
    Json entry = node_json(run, node.index);
    entry["distance"] = node.distance;
    list.push_back(std::move(entry));
  }
  return list;
}

Json face_grid_json(const setup::SurfaceRun& run, std::size_t f, std::size_t n) {
  const geometry::BSplineSurface& surface = run.faces[f].surface;
  const geometry::BSplineSurface& field = run.fit.fields[f];
  const geometry::ParameterRectangle r = surface.domain();
  const std::vector<double> t = evenly(r.u_first, r.u_last, n);
  const std::vector<double> s = evenly(r.v_first, r.v_last, n);
  Json points = Json::array();
  Json deflections = Json::array();
  for (const double u : t) {
    for (const double v : s) {
      points.push_back(vec3_json(surface.point(u, v)));
      deflections.push_back(vec3_json(field.point(u, v)));
    }
  }
  return {{"id", run.faces[f].id},
          {"name", run.info[f].name},
          {"kind", geometry::to_string(run.info[f].kind)},
          {"parameter_range", {{"t", {r.u_first, r.u_last}}, {"s", {r.v_first, r.v_last}}}},
          {"knots", {{"t", field.u_breakpoints()}, {"s", field.v_breakpoints()}}},
          {"grid", {{"size", n}, {"t", t}, {"s", s}, {"points", points}, {"deflections", deflections}}}};
}

}  // namespace hotmesh::app::serve
