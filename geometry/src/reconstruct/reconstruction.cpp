// hotmesh geometry: section 4.2, reconstruction of the deflected curve. Nodes are projected on
// r(t), sorted by t_j, merged where they coincide, and interpolated (eq. 21) by a degree-q
// B-spline: c(t_j) = Q_j + delta_j (form curve) or d(t_j) = delta_j (form displacement).
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "hotmesh/geometry/curve_projector.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/geometry/interpolation.hpp"
#include "hotmesh/geometry/reconstruction.hpp"
#include "reconstruct/node_list.hpp"

namespace hotmesh::geometry {

namespace {

using detail::format;
using detail::list_nodes;

/// Nodes whose parameters differ by less than this fraction of the range are one node.
constexpr double kSameParameter = 1e-10;

/// An FEM node placed on the undeformed curve.
struct PlacedNode {
  double t;
  double distance;
  Vec2 point;
  Vec2 deflection;
  std::size_t index;
};

void check_inputs(const CurveSamples& samples, const ReconstructionOptions& options) {
  if (options.degree < 1 || options.degree > kMaxReconstructionDegree) {
    throw InputError::in(samples.source, "the degree of the deflected curve must be 1 to " +
                                             std::to_string(kMaxReconstructionDegree) + ", got " +
                                             std::to_string(options.degree));
  }
  if (!std::isfinite(options.tolerance) || options.tolerance < 0.0 ||
      !(options.relative_tolerance > 0.0) || !std::isfinite(options.relative_tolerance)) {
    throw InputError::in(samples.source, "the node distance tolerance must be a finite positive number");
  }
  if (samples.deflections.size() != samples.size()) {
    throw InputError::in(samples.source, "every FEM node needs a deflection");
  }
  if (samples.size() == 0) throw InputError::in(samples.source, "there are no FEM nodes");
  for (std::size_t j = 0; j < samples.size(); ++j) {
    if (!is_finite(samples.points[j]) || !is_finite(samples.deflections[j])) {
      throw InputError::in(samples.source, samples.label(j) + " has a coordinate or deflection that is not finite");
    }
  }
}

/// Sorted by t; groups of nodes at one parameter become one node (their mean), provided their
/// deflections agree within the tolerance.
std::vector<PlacedNode> merge_duplicates(std::vector<PlacedNode> nodes, const CurveSamples& samples, double range,
                                         double tolerance, std::size_t& merged) {
  std::stable_sort(nodes.begin(), nodes.end(), [](const PlacedNode& a, const PlacedNode& b) { return a.t < b.t; });
  std::vector<PlacedNode> result;
  merged = 0;
  for (std::size_t i = 0; i < nodes.size();) {
    std::size_t end = i + 1;
    while (end < nodes.size() && nodes[end].t - nodes[i].t <= kSameParameter * range) ++end;
    PlacedNode mean = nodes[i];
    double t_offset = 0.0;  // mean t as first + mean offset: exact when all t are equal
    for (std::size_t k = i + 1; k < end; ++k) {
      if (distance(nodes[k].deflection, nodes[i].deflection) > tolerance) {
        throw InputError::in(samples.source, samples.label(nodes[i].index) + " and " + samples.label(nodes[k].index) +
                                                 " are at the same place on the curve (t = " + format(nodes[i].t) +
                                                 ") but their deflections differ by " +
                                                 format(distance(nodes[k].deflection, nodes[i].deflection)));
      }
      t_offset += nodes[k].t - nodes[i].t;
      mean.point += nodes[k].point;
      mean.deflection += nodes[k].deflection;
      mean.distance = std::max(mean.distance, nodes[k].distance);
    }
    const auto count = static_cast<double>(end - i);
    mean.t = nodes[i].t + t_offset / count;
    mean.point = mean.point / count;
    mean.deflection = mean.deflection / count;
    merged += end - i - 1;
    result.push_back(mean);
    i = end;
  }
  return result;
}

/// Eq. (21) cannot be solved to double precision: nodes bunched so closely, for the curve's
/// length, that the degree-q basis cannot tell them apart (one node far from the others makes
/// the rest such a bunch). Names the closest pair.
[[noreturn]] void refuse_bunched_nodes(const std::vector<PlacedNode>& nodes, const CurveSamples& samples,
                                       double range, int degree, const std::string& why) {
  std::size_t closest = 0;
  for (std::size_t j = 1; j + 1 < nodes.size(); ++j) {
    if (nodes[j + 1].t - nodes[j].t < nodes[closest + 1].t - nodes[closest].t) closest = j;
  }
  throw InputError::in(samples.source,
                       "the FEM nodes cannot be interpolated by a curve of degree " + std::to_string(degree) + " (" +
                           why + "): " + samples.label(nodes[closest].index) + " and " +
                           samples.label(nodes[closest + 1].index) + " are " +
                           format((nodes[closest + 1].t - nodes[closest].t) / range) +
                           " of the curve's length apart; look for a node far from the others, or use degree 1");
}

/// Eq. (21) on nodes sorted by t: the interpolant, the deflected curve and the report.
Reconstruction interpolate_nodes(const BSplineCurve2d& undeformed, std::vector<PlacedNode> nodes,
                                 const CurveSamples& samples, const ReconstructionOptions& options,
                                 ReconstructionReport report) {
  const double range = undeformed.last_parameter() - undeformed.first_parameter();
  nodes = merge_duplicates(std::move(nodes), samples, range, report.tolerance, report.merged_duplicates);
  if (nodes.size() < static_cast<std::size_t>(options.degree) + 1) {
    throw InputError::in(samples.source, "a deflected curve of degree " + std::to_string(options.degree) +
                                             " needs at least " + std::to_string(options.degree + 1) +
                                             " FEM nodes at distinct places on the curve, got " +
                                             std::to_string(nodes.size()));
  }
  std::vector<double> parameters(nodes.size());
  std::vector<Vec2> values(nodes.size());
  for (std::size_t j = 0; j < nodes.size(); ++j) {
    parameters[j] = nodes[j].t;
    values[j] = options.form == DeflectionForm::curve ? nodes[j].point + nodes[j].deflection : nodes[j].deflection;
    report.max_node_distance_to_cad = std::max(report.max_node_distance_to_cad, nodes[j].distance);
  }
  std::optional<BSplineCurve2d> solved;
  try {
    solved = interpolate(parameters, values, options.degree);
  } catch (const std::invalid_argument& e) {
    refuse_bunched_nodes(nodes, samples, range, options.degree, e.what());
  }
  BSplineCurve2d interpolant = std::move(*solved);
  for (std::size_t j = 0; j < nodes.size(); ++j) {
    report.max_node_residual = std::max(report.max_node_residual, distance(interpolant.point(parameters[j]), values[j]));
  }
  report.used_nodes = nodes.size();
  report.fem_first = parameters.front();
  report.fem_last = parameters.back();
  return {DeflectedCurve(undeformed, std::move(interpolant), options.form), std::move(report)};
}

ReconstructionReport start_report(const BSplineCurve2d& undeformed, const CurveSamples& samples,
                                  const ReconstructionOptions& options) {
  ReconstructionReport report;
  report.nodes = samples.size();
  report.degree = options.degree;
  report.form = options.form;
  report.curve_first = undeformed.first_parameter();
  report.curve_last = undeformed.last_parameter();
  report.max_out_of_plane_deflection = samples.max_out_of_plane_deflection;
  return report;
}

}  // namespace

Reconstruction reconstruct(const BSplineCurve2d& undeformed, const CurveSamples& samples,
                           const ReconstructionOptions& options) {
  check_inputs(samples, options);
  const CurveProjector projector{DeflectedCurve(undeformed)};
  ReconstructionReport report = start_report(undeformed, samples, options);
  report.tolerance = options.tolerance > 0.0 ? options.tolerance : options.relative_tolerance * projector.length_scale();

  // Project every Q_j on r(t) (global search: the nodes come in no particular order).
  std::vector<PlacedNode> nodes;
  nodes.reserve(samples.size());
  for (std::size_t j = 0; j < samples.size(); ++j) {
    const CurveProjection p = projector.project(samples.points[j], 0.0);
    if (p.distance > report.tolerance) {
      report.rejected_nodes.push_back({j, samples.label(j), p.distance, p.parameter});
      continue;
    }
    nodes.push_back({p.parameter, p.distance, samples.points[j], samples.deflections[j], j});
  }
  if (!report.rejected_nodes.empty() && options.far_nodes == FarNodePolicy::reject) {
    const std::string how = options.tolerance > 0.0 ? "the given tolerance"
                                                    : "the default tolerance, " + format(options.relative_tolerance) +
                                                          " of the curve's size " + format(projector.length_scale());
    throw InputError::in(samples.source, std::to_string(report.rejected_nodes.size()) + " of " +
                                             std::to_string(samples.size()) + " FEM nodes are farther than " +
                                             format(report.tolerance) + " (" + how + ") from the CAD curve: " +
                                             list_nodes(report.rejected_nodes));
  }
  return interpolate_nodes(undeformed, std::move(nodes), samples, options, std::move(report));
}

Reconstruction reconstruct_from_nodes(const CurveSamples& samples, const ReconstructionOptions& options) {
  check_inputs(samples, options);
  // Coincident nodes first (they would give equal chord parameters), then the order.
  Vec2 lo = samples.points.front();
  Vec2 hi = lo;
  for (const Vec2& q : samples.points) {
    lo = {std::min(lo.x, q.x), std::min(lo.y, q.y)};
    hi = {std::max(hi.x, q.x), std::max(hi.y, q.y)};
  }
  const double size = distance(lo, hi);
  const double tolerance = options.tolerance > 0.0 ? options.tolerance : options.relative_tolerance * size;
  const std::vector<std::size_t> order = order_along_curve(samples.points);

  // Distinct points along the order, with cumulative chord length as parameter.
  std::vector<std::size_t> distinct;
  std::vector<PlacedNode> nodes;
  double length = 0.0;
  for (const std::size_t j : order) {
    if (!distinct.empty()) {
      const double step = distance(samples.points[j], samples.points[distinct.back()]);
      if (step <= kSameParameter * size) {
        nodes.push_back({length, 0.0, samples.points[j], samples.deflections[j], j});
        continue;  // same point: merged with its predecessor below
      }
      length += step;
    }
    distinct.push_back(j);
    nodes.push_back({length, 0.0, samples.points[j], samples.deflections[j], j});
  }
  if (distinct.size() < 2) {
    throw InputError::in(samples.source, "the FEM nodes of a curve without CAD must be at two places at least");
  }
  std::vector<double> parameters;
  std::vector<Vec2> points;
  for (const std::size_t j : distinct) points.push_back(samples.points[j]);
  for (PlacedNode& node : nodes) node.t /= length;
  for (const PlacedNode& node : nodes) {
    if (parameters.empty() || node.t > parameters.back()) parameters.push_back(node.t);
  }
  parameters.back() = 1.0;
  const BSplineCurve2d undeformed = BSplineCurve2d::polyline(parameters, points);
  ReconstructionReport report = start_report(undeformed, samples, options);
  report.tolerance = tolerance;
  return interpolate_nodes(undeformed, std::move(nodes), samples, options, std::move(report));
}

CurveSamples curve_samples(const DeflectionSamples& samples, const Axis* axis) {
  return axis ? meridional_samples(samples, *axis) : planar_samples(samples);
}

Reconstruction fit_curve(const CurveSamples& nodes, const BSplineCurve2d* undeformed,
                         const ReconstructionOptions& options) {
  return undeformed ? reconstruct(*undeformed, nodes, options) : reconstruct_from_nodes(nodes, options);
}

}  // namespace hotmesh::geometry
