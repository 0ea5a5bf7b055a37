// hotmesh geometry: a clamped tensor-product B-spline (optionally rational) surface, the form
// in which CAD systems export their faces (section 4.2: "a set of B-Splines (or NURBS)
// surfaces"). Used to give a CAD face in B-spline form and to write surfaces to STEP/IGES, and
// as a deflection field d(u, v) over a face (vector poles) for the deformed face S + d.
// Evaluation is const, allocation-free and thread-safe.
#pragma once

#include <cstddef>
#include <vector>

#include "hotmesh/geometry/parametric_surface.hpp"
#include "hotmesh/core/vec3.hpp"

namespace hotmesh::geometry {

class BSplineSurface {
 public:
  /// Flat, clamped knot vectors in u and v (as BSplineCurve2d); poles u-major,
  /// poles[i * v_count + j] with u_count = u_knots.size() - u_degree - 1; weights empty or one
  /// per pole, positive. Throws std::invalid_argument otherwise.
  BSplineSurface(int u_degree, int v_degree, std::vector<double> u_knots, std::vector<double> v_knots,
                 std::vector<Vec3> poles, std::vector<double> weights = {});

  int u_degree() const { return u_degree_; }
  int v_degree() const { return v_degree_; }
  const std::vector<double>& u_knots() const { return u_knots_; }
  const std::vector<double>& v_knots() const { return v_knots_; }
  std::size_t u_count() const { return u_knots_.size() - static_cast<std::size_t>(u_degree_) - 1; }
  std::size_t v_count() const { return v_knots_.size() - static_cast<std::size_t>(v_degree_) - 1; }
  const std::vector<Vec3>& poles() const { return poles_; }
  const std::vector<double>& weights() const { return weights_; }
  bool is_rational() const { return !weights_.empty(); }
  double u_first() const { return u_knots_[static_cast<std::size_t>(u_degree_)]; }
  double u_last() const { return u_knots_[u_count()]; }
  double v_first() const { return v_knots_[static_cast<std::size_t>(v_degree_)]; }
  double v_last() const { return v_knots_[v_count()]; }

  ParameterRectangle domain() const { return {u_first(), u_last(), v_first(), v_last()}; }

  /// The point at (u, v), clamped to the parameter ranges.
  Vec3 point(double u, double v) const;
  /// The point and its first and second partial derivatives at (u, v), clamped to the
  /// parameter ranges (at a knot: the derivatives of the span that starts there; at the last
  /// parameter, of the last span).
  SurfaceDerivatives derivatives(double u, double v) const;
  /// The same without clamping: beyond the parameter ranges, the polynomial (rational) pieces
  /// at the edges continued. Meant for a short way past the edges (a face extended beyond
  /// a free edge); far out the continuation has no meaning, and weights may vanish.
  SurfaceDerivatives continued_derivatives(double u, double v) const;
  /// The distinct knot values from u_first() to u_last() (v_first() to v_last()): where the
  /// surface may be less smooth than its degree allows.
  std::vector<double> u_breakpoints() const;
  std::vector<double> v_breakpoints() const;

 private:
  int u_degree_;
  int v_degree_;
  std::vector<double> u_knots_;
  std::vector<double> v_knots_;
  std::vector<Vec3> poles_;
  std::vector<double> weights_;
};

}  // namespace hotmesh::geometry
