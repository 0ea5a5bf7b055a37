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
#pragma once

#include <cstddef>
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

/// Joins the `fields` (one per face, non-rational, degree q each way) along `sides`. Corners
/// lists the groups of face corners that lie at one point of the wall and end a shared side.
/// Returns the sides that could not be joined (their fields' degrees differ along the edge).
std::vector<SharedSide> join_fields(std::vector<BSplineSurface>& fields, std::span<const SharedSide> sides,
                                    std::span<const std::vector<FaceCorner>> corners);

}  // namespace hotmesh::geometry::detail
