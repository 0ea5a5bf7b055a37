// hotmesh geometry: eq. (21), B-spline interpolation with averaged knots. The banded
// collocation matrix is built, factored and solved by OpenCASCADE's BSplCLib (1-based arrays,
// band storage of width 2q + 1; LU without pivoting, valid for Schoenberg-Whitney parameters).
#include "hotmesh/geometry/interpolation.hpp"

#include <BSplCLib.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <math_Matrix.hxx>

#include <cmath>
#include <stdexcept>
#include <string>

namespace hotmesh::geometry {

namespace {

void check_parameters(std::span<const double> parameters, int degree) {
  if (degree < 1 || degree > kMaxBSplineDegree) {
    throw std::invalid_argument("interpolation degree " + std::to_string(degree) + " is out of range");
  }
  if (parameters.size() < static_cast<std::size_t>(degree) + 1) {
    throw std::invalid_argument("interpolation of degree " + std::to_string(degree) + " needs at least " +
                                std::to_string(degree + 1) + " points, got " + std::to_string(parameters.size()));
  }
  for (std::size_t j = 0; j < parameters.size(); ++j) {
    if (!std::isfinite(parameters[j]) || (j > 0 && !(parameters[j] > parameters[j - 1]))) {
      throw std::invalid_argument("interpolation parameters must be finite and strictly increasing");
    }
  }
}

}  // namespace

std::vector<double> averaged_knots(std::span<const double> parameters, int degree) {
  check_parameters(parameters, degree);
  const auto p = static_cast<std::size_t>(degree);
  const std::size_t n = parameters.size();  // poles
  std::vector<double> knots(n + p + 1);
  for (std::size_t i = 0; i <= p; ++i) {
    knots[i] = parameters.front();
    knots[n + i] = parameters.back();
  }
  // The NURBS Book eq. (9.8): u_{j+p} = (1/p) sum_{i=j}^{j+p-1} t_i, j = 1..n-1-p.
  for (std::size_t j = 1; j + p < n; ++j) {
    double sum = 0.0;
    for (std::size_t i = j; i < j + p; ++i) sum += parameters[i];
    knots[j + p] = sum / static_cast<double>(p);
  }
  return knots;
}

BSplineCurve2d interpolate(std::span<const double> parameters, std::span<const Vec2> values, int degree) {
  if (parameters.size() != values.size()) {
    throw std::invalid_argument("interpolation needs one value per parameter");
  }
  std::vector<double> knots = averaged_knots(parameters, degree);
  const auto n = static_cast<Standard_Integer>(parameters.size());

  TColStd_Array1OfReal flat_knots(1, static_cast<Standard_Integer>(knots.size()));
  for (Standard_Integer i = 1; i <= flat_knots.Upper(); ++i) flat_knots(i) = knots[static_cast<std::size_t>(i - 1)];
  TColStd_Array1OfReal params(1, n);
  TColStd_Array1OfInteger contact_orders(1, n);
  contact_orders.Init(0);  // values only, no derivative conditions
  // Row j of the right-hand side (and, after the solve, pole j): two consecutive reals.
  std::vector<double> rhs(2 * parameters.size());
  for (Standard_Integer j = 1; j <= n; ++j) {
    const auto k = static_cast<std::size_t>(j - 1);
    params(j) = parameters[k];
    rhs[2 * k] = values[k].x;
    rhs[2 * k + 1] = values[k].y;
  }

  math_Matrix band(1, n, 1, 2 * degree + 1);
  Standard_Integer upper = 0;
  Standard_Integer lower = 0;
  Standard_Integer pivot_problem = 0;
  try {
    if (BSplCLib::BuildBSpMatrix(params, contact_orders, flat_knots, degree, band, upper, lower) != 0 ||
        BSplCLib::FactorBandedMatrix(band, upper, lower, pivot_problem) != 0 ||
        BSplCLib::SolveBandedSystem(band, upper, lower, 2, rhs[0]) != 0) {
      throw std::invalid_argument("interpolation system is singular (row " + std::to_string(pivot_problem) + ")");
    }
  } catch (const Standard_Failure& e) {
    throw std::invalid_argument(std::string("interpolation failed: ") + e.GetMessageString());
  }

  std::vector<Vec2> poles(parameters.size());
  for (std::size_t k = 0; k < poles.size(); ++k) poles[k] = {rhs[2 * k], rhs[2 * k + 1]};
  return BSplineCurve2d(degree, std::move(knots), std::move(poles));
}

}  // namespace hotmesh::geometry
