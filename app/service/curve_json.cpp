// hotmesh serve: curves and node fits as JSON (see curve_json.hpp).
#include "service/curve_json.hpp"

#include <algorithm>
#include <set>

namespace hotmesh::app::serve {

namespace {

Json pair(const geometry::Vec2& v) { return Json::array({v.x, v.y}); }

}  // namespace

Json curve_json(const geometry::BSplineCurve2d& exact, const geometry::DeflectedCurve& curve,
                const std::vector<double>& t, double lambda) {
  Json poles = Json::array();
  for (const geometry::Vec2& p : exact.poles()) poles.push_back(pair(p));
  Json samples = Json::array();
  for (const double s : t) {
    const geometry::Vec2 p = curve.point(s, lambda);
    samples.push_back(Json::array({s, p.x, p.y}));
  }
  return {{"degree", exact.degree()},
          {"knots", exact.knots()},
          {"poles", poles},
          {"weights", exact.is_rational() ? Json(exact.weights()) : Json(nullptr)},
          {"samples", samples}};
}

Json node_fits_json(const setup::CurveRun& run, const geometry::CurveProjector& undeformed) {
  const geometry::CurveSamples& nodes = run.nodes;
  const geometry::DeflectedCurve& curve = run.fit.curve;
  std::set<std::size_t> rejected;
  for (const auto& node : run.fit.report.rejected_nodes) rejected.insert(node.index);
  const bool displacement = run.fit.report.form == geometry::DeflectionForm::displacement;
  Json list = Json::array();
  for (std::size_t j = 0; j < nodes.size(); ++j) {
    const geometry::Vec2 q = nodes.points[j];
    const geometry::Vec2 delta = nodes.deflections[j];
    const geometry::CurveProjection on = undeformed.project(q, 0.0);
    Json residual = nullptr;
    if (!rejected.contains(j)) {
      const geometry::Vec2 miss = displacement ? curve.deflection(on.parameter) - delta
                                               : curve.point(on.parameter, 1.0) - (q + delta);
      residual = geometry::norm(miss);
    }
    list.push_back({{"index", j},
                    {"label", nodes.label(j)},
                    {"id", j < nodes.ids.size() ? Json(nodes.ids[j]) : Json(nullptr)},
                    {"line", j < nodes.lines.size() ? Json(nodes.lines[j]) : Json(nullptr)},
                    {"point", pair(q)},
                    {"deflection", pair(delta)},
                    {"parameter", on.parameter},
                    {"distance", on.distance},
                    {"residual", residual},
                    {"rejected", rejected.contains(j)}});
  }
  return list;
}

}  // namespace hotmesh::app::serve
