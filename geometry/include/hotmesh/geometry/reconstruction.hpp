// hotmesh geometry: reconstruction of the deflected boundary from FEM node deflections, the
// paper's section 4.2. The FEM nodes Q_j are projected onto the undeformed curve r(t) to get
// t_j (nodes farther than a tolerance are reported), sorted by t_j (which recovers their order
// along the CAD curve), merged where they coincide, and a degree-q B-spline is interpolated
// through them (eq. 21) by a banded LU solve: c(t_j) = Q_j + delta_j (form curve) or
// d(t_j) = delta_j (form displacement). Without a CAD curve the nodes themselves define r(t):
// they are ordered along the curve they sample and joined by the degree-1 curve through them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "hotmesh/geometry/axis.hpp"
#include "hotmesh/geometry/deflected_curve.hpp"
#include "hotmesh/geometry/deflection_samples.hpp"

namespace hotmesh::geometry {

/// FEM nodes and deflections in the plane of a curve: (x, y) for 2D cases, (r, z) in the
/// meridional plane for axisymmetric ones.
struct CurveSamples {
  std::vector<Vec2> points;        ///< Q_j
  std::vector<Vec2> deflections;   ///< delta_j
  std::vector<std::int64_t> ids;   ///< FEM node ids; empty if the table had none
  std::vector<std::size_t> lines;  ///< source line per node; empty if not from a file
  std::string source;              ///< for messages
  /// Largest deflection component out of the curve's plane that was dropped: the
  /// circumferential one (about the axis) for meridional samples, z for planar ones.
  double max_out_of_plane_deflection = 0.0;

  std::size_t size() const { return points.size(); }
  /// "node 17 (line 19)", "node 17", "line 19" or "sample 3" for sample j (0-based).
  std::string label(std::size_t j) const;
};

/// Planar (x, y) samples for a 2D case. Throws hotmesh::InputError for other frames.
CurveSamples planar_samples(const DeflectionSamples& samples);
/// (r, z) samples about `axis`: cartesian points and deflections are converted (the
/// deflection's radial and axial components at the node's angle; the circumferential one is
/// dropped and reported); meridional samples are taken as they are. Throws hotmesh::InputError
/// for planar samples.
CurveSamples meridional_samples(const DeflectionSamples& samples, const Axis& axis);
/// Samples in the plane of a 2D axisymmetric mesh, whose (x, y) are (z, r) about `axis`: the
/// meridional_samples with the two coordinates of every point and deflection exchanged.
CurveSamples axial_plane_samples(const DeflectionSamples& samples, const Axis& axis);

/// What to do with FEM nodes farther than the tolerance from the undeformed curve.
enum class FarNodePolicy {
  reject,  ///< throw hotmesh::InputError listing them (the default)
  drop,    ///< leave them out and list them in the report
};

/// The highest degree q of a deflected curve (eq. 21) hotmesh takes.
inline constexpr int kMaxReconstructionDegree = 5;

struct ReconstructionOptions {
  int degree = 1;  ///< q, 1..5; 1 is the paper's choice (linear FEM elements)
  DeflectionForm form = DeflectionForm::curve;
  /// Largest distance of an FEM node from the undeformed curve, in model units. Zero (the
  /// default) means relative_tolerance times the curve's size (its bounding-box diagonal).
  double tolerance = 0.0;
  double relative_tolerance = 1e-3;
  FarNodePolicy far_nodes = FarNodePolicy::reject;
};

/// One FEM node in a report.
struct NodeDistance {
  std::size_t index = 0;  ///< 0-based position in the samples
  std::string label;      ///< as CurveSamples::label
  double distance = 0.0;  ///< to the undeformed curve
  double parameter = 0.0; ///< t of its projection
};

struct ReconstructionReport {
  std::size_t nodes = 0;              ///< FEM nodes given
  std::size_t used_nodes = 0;         ///< interpolation points after merging and dropping
  std::size_t merged_duplicates = 0;  ///< nodes merged into another at the same place
  int degree = 1;
  DeflectionForm form = DeflectionForm::curve;
  double tolerance = 0.0;             ///< the distance tolerance used
  double curve_first = 0.0, curve_last = 0.0;  ///< parameter range of r(t)
  double fem_first = 0.0, fem_last = 0.0;      ///< parameter range covered by the nodes
  double max_node_distance_to_cad = 0.0;       ///< over the nodes used
  double max_node_residual = 0.0;  ///< max |interpolant(t_j) - value_j|: the solve's accuracy
  double max_out_of_plane_deflection = 0.0;
  std::vector<NodeDistance> rejected_nodes;  ///< dropped for distance (FarNodePolicy::drop)
};

struct Reconstruction {
  DeflectedCurve curve;
  ReconstructionReport report;
};

/// Section 4.2 with a CAD curve r(t). Throws hotmesh::InputError for options out of range,
/// nodes too far from the curve (policy reject), nodes at one place with different
/// deflections, or fewer than degree + 1 distinct nodes.
Reconstruction reconstruct(const BSplineCurve2d& undeformed, const CurveSamples& samples,
                           const ReconstructionOptions& options = {});

/// Section 4.2 without a CAD curve: the nodes are ordered along the curve they sample
/// (order_along_curve), r(t) is the degree-1 curve through them with t the cumulative chord
/// length scaled to [0, 1], and the deflection is interpolated at those t.
Reconstruction reconstruct_from_nodes(const CurveSamples& samples, const ReconstructionOptions& options = {});

/// Section 4.2 from a node table, in two steps: the one pipeline behind the case file's
/// deflections, `hotmesh curve`, `hotmesh check` and the service.
/// 1. The table's nodes in the plane of the curve: (x, y) without an axis (planar_samples),
///    (r, z) about `axis` (meridional_samples).
CurveSamples curve_samples(const DeflectionSamples& samples, const Axis* axis);
/// 2. Eq. (21) on the CAD curve `undeformed` (reconstruct), or without one on the curve the
///    nodes define (reconstruct_from_nodes).
Reconstruction fit_curve(const CurveSamples& nodes, const BSplineCurve2d* undeformed,
                         const ReconstructionOptions& options = {});

/// An order of unordered points sampled along one open curve: the longest path of their
/// Euclidean minimum spanning tree gives the spine; points off it are inserted where they
/// project onto it. The first point is the end with the smaller x (then y). A closed curve is
/// opened at its largest gap.
std::vector<std::size_t> order_along_curve(std::span<const Vec2> points);

}  // namespace hotmesh::geometry
