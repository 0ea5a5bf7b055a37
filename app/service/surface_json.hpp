// hotmesh serve: deflection fields on CAD faces as JSON for the API (section 4.2 on B-spline
// surfaces S(t, s)): each FEM node where it lies on a face, (t_j, s_j), with its distance to the
// face and the residual |d(t_j, s_j) - delta_j| of the field there; the nodes left out; and each
// face as a grid of samples of S(t, s) and d(t, s), from which a page draws S + A d.
#pragma once

#include <cstddef>
#include <span>

#include "hotmesh/setup/face_fit.hpp"
#include "service/json_fields.hpp"

namespace hotmesh::app::serve {

/// One entry per placement of run.fit (a node on an edge two faces share has one per face):
/// {"index", "label", "id", "line", "face" (CAD number), "t", "s", "point", "deflection",
/// "distance", "residual"}. `residuals` as placement_residuals gives them.
Json placements_json(const setup::SurfaceRun& run, std::span<const double> residuals);

/// The nodes left out for their distance from every face: {"index", "label", "id", "line",
/// "point", "deflection", "distance"}.
Json left_out_json(const setup::SurfaceRun& run);

/// Face f of the run: {"id", "name", "kind", "parameter_range": {"t", "s"}, "knots": {"t", "s"}
/// (the breakpoints of d), "grid": {"size": n, "t": [n], "s": [n], "points": [n * n],
/// "deflections": [n * n]}}, grid entry i n + j at (t_i, s_j): S(t_i, s_j) and d(t_i, s_j).
Json face_grid_json(const setup::SurfaceRun& run, std::size_t f, std::size_t n);

}  // namespace hotmesh::app::serve
