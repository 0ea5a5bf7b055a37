// hotmesh geometry (internal): the deflection fields d(t, s) of CAD faces made to agree along
// the edges the faces share, so that the deformed faces S + d meet there (issue 23, item 1).
//
// Each face's field is fitted on its own (surface_fit.hpp); a node on a shared edge is a sample
// of both fields, but between such nodes two fits differ by their fitting error. A clamped
// B-spline surface's boundary curve along a side depends only on that side's row of poles and
// on the knots along it. Where the two faces parametrise the edge affinely to each other (the
// same curve, the same speed up to a constant: the rule for faces that a CAD system splits
// from one surface, or builds on one edge curve), the fields are made to meet exactly:
//  1. knots are inserted (Boehm) into each field along the edge until both have the same knots
//     there, mapped from one face's parameter to the other's; the fields do not change;
//  2. the rows of poles along the edge are replaced by their mean, and the poles at the
//     corners by the mean over every face that meets there.
// Replacing a boundary row changes a field only within one knot span of the edge, by half
// the difference of the two fits: both fields then pass through the mean of their values at
// the edge's nodes. Fields that are polynomials of degree <= q, which both fits reproduce, are
// left as they were.
//
// Where the faces run along the edge at speeds that are not in a constant ratio (x on a's side
// is y = phi(x) on b's, phi not affine), a B-spline in x is not one in y, and the fields are
// made to meet to a tolerance instead:
//  3. each field takes the images phi(k) (phi^-1(k)) of the other's knots along the edge, so
//     the breaks of the target below fall on knots of both;
//  4. the target m(x) = (d_a(x) + d_b(phi(x))) / 2, plus a function linear in x that takes it
//     to the corner poles' means at the ends, taken at 8 points per knot span of either side,
//     is fitted by least squares in each face's own parameter with its row of poles along the
//     edge: the corner poles kept, the change of the others small where the samples barely
//     reach them (a side covering part of the other's);
//  5. while the two rows differ by more than the tolerance somewhere, the knot spans where
//     they differ by more than a tenth of it are halved in both fields (at x and at phi(x))
//     and steps 1, 2 and 4 done again, at most kMaxHalvings times.
// Fields that meet along the edge already (polynomials of degree <= q in both parameters) keep
// their knots, and their rows change by round-off. An edge whose fields still differ by more
// than the tolerance after the last halving is left fitted as well as it got, and not counted
// as joined.
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "hotmesh/geometry/bspline_surface.hpp"

namespace hotmesh::geometry::detail {

/// Side k of a parameter rectangle: 0 v first, 1 v last (both run along u), 2 u first, 3 u
/// last (along v).
struct FaceSide {
  std::size_t face = 0;
  int side = 0;
};

/// One edge two faces share, side to side: the point at fraction f along a's side is the
/// point at fraction f (or 1 - f, `reversed`) along b's side.
struct SharedSide {
  FaceSide a;
  FaceSide b;
  bool reversed = false;
};

/// A corner of a face's rectangle: 0 (u first, v first), 1 (u last, v first), 2 (u first,
/// v last), 3 (u last, v last).
struct FaceCorner {
  std::size_t face = 0;
  int corner = 0;
};

/// An edge two faces share whose parameters along it are not affine to each other: the point
/// of a's side at a's parameter x along it is the point of b's side at b's parameter to_b(x)
/// (a monotone map). a's side may be part of b's side only (b's side is then shared with other
/// faces too); to_a is the inverse, called on the image of a's side only.
struct UnevenSide {
  FaceSide a;
  FaceSide b;
  std::function<double(double)> to_b;
  std::function<double(double)> to_a;
};

/// How far the joins went.
struct JoinOutcome {
  std::size_t joined = 0;  ///< edges whose fields meet: affine ones, and uneven ones within the tolerance
  std::vector<SharedSide> left;  ///< affine sides not joined (their fields' degrees differ along the edge)
  std::vector<double> uneven_gaps;  ///< per uneven side, max |d_a - d_b| along it after the join
};

/// A value a field's side should take at parameter x (u along sides 0 and 1, v along 2 and 3),
/// as the change from its value there.
struct SideTarget {
  double x = 0.0;
  Vec3 change;
};

/// Fits the row of poles along `side` of a field (non-rational) to the targets by least
/// squares, its corner poles kept or not, the rest of the field as it was.
void fit_side_row(BSplineSurface& field, int side, std::span<const SideTarget> targets, bool keep_corners);

/// Inserts knot x once into the field along u (else v), the field unchanged (Boehm); not at
/// an end or where the knot's multiplicity is already the degree. Returns whether it did.
bool insert_knot(BSplineSurface& field, bool u, double x);

/// At most this many halvings of the knot spans along an uneven edge (step 5).
inline constexpr int kMaxHalvings = 5;

/// Joins the `fields` (one per face, non-rational, degree q each way) along the affine `sides`
/// exactly and along the `uneven` ones to `tolerance` (a distance between deflections). Corners
/// lists the groups of face corners that lie at one point of the wall and end a shared side.
JoinOutcome join_fields(std::vector<BSplineSurface>& fields, std::span<const SharedSide> sides,
                        std::span<const UnevenSide> uneven, std::span<const std::vector<FaceCorner>> corners,
                        double tolerance);

}  // namespace hotmesh::geometry::detail
