// hotmesh geometry: closest point on a stage c_lambda(t) of a deflected curve (section 4.2:
// "the problem of projecting a point to the curve c(t) is solved using Newton iterations ...
// using the De Boor algorithm").
//
// Warm start (a hint t from an earlier projection of a nearby point): safeguarded Newton on
// the squared distance from the hint. Cold start (no hint): a global search first. At
// construction every stage is sampled densely enough that the chord polyline between samples
// deviates from the curve by at most `sampling_deviation()` (for every lambda, because c_lambda
// is affine in lambda); boxes around the sample segments of r and c_1 hold the segments of every
// stage, so one tree of boxes serves all lambda. A query finds the nearest polyline segment,
// then every run of segments within twice the deviation of it, and runs Newton from each run:
// the true closest point lies near one of them, so near-touching branches cannot fool it.
//
// project() and at() are const, lock-free and allocation-free: safe and cheap inside parallel
// loops over mesh nodes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "hotmesh/geometry/boundary_shape.hpp"
#include "hotmesh/geometry/deflected_curve.hpp"

namespace hotmesh::geometry {

/// No earlier projection to start from (a curve parameter): the search is global.
inline constexpr double kNoCurveHint = kNoHint.t;

struct CurveProjection {
  Vec2 point;
  /// Unit normal: the unit tangent turned by +90 degrees, i.e. to the left when walking along
  /// increasing t. At a corner of the curve (a C0 knot), the bisector of the two one-sided
  /// normals.
  Vec2 normal;
  Vec2 tangent;  ///< unit tangent along increasing t (at a corner: normal turned by -90 degrees)
  double parameter = 0.0;
  double distance = 0.0;  ///< from the projected point (0 for at())
  int iterations = 0;     ///< Newton iterations used (0 for at())
};

class CurveProjector {
 public:
  explicit CurveProjector(DeflectedCurve curve);

  const DeflectedCurve& curve() const { return curve_; }
  /// Diagonal of the box that holds every stage: the length scale of tolerances.
  double length_scale() const { return scale_; }
  std::size_t sample_count() const { return samples_.size(); }
  /// Bound on the distance between the sample polyline and the curve, for every stage.
  double sampling_deviation() const { return deviation_; }

  /// Closest point to p on c_lambda (lambda clamped to [0, 1]); with kNoCurveHint, global. With a
  /// range, the closest point of the part of c_lambda with t in it (its ends are clamped to
  /// the parameter range and taken to the nearest piece ends: corners are piece ends).
  CurveProjection project(const Vec2& p, double lambda, double hint = kNoCurveHint,
                          const ParameterRange& range = {}) const;
  /// The point of c_lambda at parameter t (clamped to the range), with tangent and normal.
  CurveProjection at(double t, double lambda) const;

 private:
  struct Sample {
    double t;
    Vec2 r;  // on the undeformed curve, lambda = 0
    Vec2 c;  // on the fully deflected curve, lambda = 1
  };
  struct Box {
    Vec2 lo;
    Vec2 hi;
  };
  struct Local {
    double t;
    std::size_t piece;
    CurveDerivatives2d value;
    double squared_distance;
    int iterations;
    bool converged;
  };

  /// Consecutive polyline segments near a query point, with the nearest point among them.
  struct Run {
    std::size_t last;         // its last segment
    double squared_distance;  // of the nearest point
    double t;                 // the nearest point's parameter
    std::size_t segment;      // the nearest point's segment
  };
  static constexpr int kMaxRuns = 16;  // the nearest runs kept by a global search

  /// The pieces [first, last] and their polyline segments [first_segment, end_segment) that a
  /// projection searches.
  struct Pieces {
    std::size_t first;
    std::size_t last;
    std::size_t first_segment;
    std::size_t end_segment;
  };

  void sample_pieces();
  void build_tree();
  Pieces pieces_in(const ParameterRange& range) const;
  Local newton(const Vec2& p, double lambda, double t, std::size_t piece, const Pieces& searched) const;
  CurveProjection global_search(const Vec2& p, double lambda, const Pieces& searched) const;
  /// Squared distance from p to segment i of the sample polyline of c_lambda; t its parameter.
  double segment_squared_distance(std::size_t i, const Vec2& p, double lambda, double& t) const;
  double nearest_segment_squared_distance(const Vec2& p, double lambda, const Pieces& searched) const;
  /// The runs of segments within squared distance `threshold` of p (at most kMaxRuns, the
  /// nearest), into `runs`; returns their count.
  int runs_within(const Vec2& p, double lambda, double threshold, const Pieces& searched, Run (&runs)[kMaxRuns]) const;
  /// Whether tree node `node` holds a segment of [first, end).
  bool overlaps(std::size_t node, std::size_t first, std::size_t end) const;
  CurveProjection finish(const Vec2& p, double lambda, const Local& local) const;

  DeflectedCurve curve_;
  std::vector<Sample> samples_;
  std::vector<std::uint32_t> segment_piece_;  // piece of the segment from sample i to i + 1
  std::vector<std::size_t> piece_segment_;    // first segment of each piece, then the segment count
  std::vector<Box> tree_;                     // implicit binary tree, leaves from index leaves_
  std::size_t leaves_ = 1;
  double scale_ = 1.0;
  double deviation_ = 0.0;
  double newton_tolerance_ = 0.0;
};

}  // namespace hotmesh::geometry
