// hotmesh serve: curves as JSON for the API: B-splines (degree, knots, poles, weights) with
// samples, and the FEM nodes of a reconstruction with their fit (section 4.2): parameter t_j
// on the undeformed curve, distance to it, and residual of the deflected curve at t_j.
#pragma once

#include <vector>

#include "hotmesh/setup/curve_fit.hpp"
#include "hotmesh/geometry/curve_projector.hpp"
#include "service/json_fields.hpp"

namespace hotmesh::app::serve {

/// {"degree", "knots", "poles": [[a, b], ...], "weights": [...] or null, "samples": [[t, a, b], ...]}:
/// `exact` with samples of stage `lambda` of `curve` at the parameters t.
Json curve_json(const geometry::BSplineCurve2d& exact, const geometry::DeflectedCurve& curve,
                const std::vector<double>& t, double lambda);

/// One entry per FEM node, in table order: {"index", "label", "id", "line", "point",
/// "deflection", "parameter", "distance", "residual", "rejected"}. The residual is
/// |c(t_j) - (Q_j + delta_j)| (form curve) or |D(t_j) - delta_j| (form displacement); it is null
/// for nodes left out for their distance. `undeformed` projects onto r(t).
Json node_fits_json(const setup::CurveRun& run, const geometry::CurveProjector& undeformed);

}  // namespace hotmesh::app::serve
