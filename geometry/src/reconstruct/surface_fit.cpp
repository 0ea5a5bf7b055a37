// hotmesh geometry: section 4.2 on a face of any shape, the deflection field d(u, v) through the
// FEM nodes' deflections in the face's parameter plane: tensor-product global interpolation
// when the nodes form a grid, regularised least squares when they are scattered.
#include "hotmesh/geometry/surface_fit.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/geometry/interpolation.hpp"
#include "reconstruct/grid_interpolation.hpp"
#include "spline/bspline_basis.hpp"

namespace hotmesh::geometry {

namespace {

/// Parameters closer than this fraction of the domain's extent are one grid line. FEM nodes on
/// a structured face mesh carry their projection's error (about 1e-9 relative); a node moved
/// along a line by this much changes the interpolated field by 1e-7 of its variation over the
/// face, which max_residual reports.
constexpr double kSameParameter = 1e-7;
/// Least squares: samples per knot span of the control net over the samples' bounding box.
constexpr double kSamplesPerSpan = 2.0;
/// Least squares: at most this many poles per sample over the whole domain (it bounds the net
/// when the samples cover a small part of the domain).
constexpr double kMaxPolesPerSample = 4.0;
/// A pivot of the normal equations below this fraction of its diagonal entry means that the
/// samples leave a degree-q polynomial field undetermined (or determined so poorly over the
/// domain that the fit would be noise, as for nodes in a strip of 1/300 of a domain with q = 3).
constexpr double kSingularPivot = 1e-10;
constexpr auto kMaxWeights = static_cast<std::size_t>(kMaxReconstructionDegree) + 2;

using SparseMatrix = Eigen::SparseMatrix<double>;
using Triplets = std::vector<Eigen::Triplet<double>>;

std::string cannot_determine(std::size_t samples, int q, const std::string& why) {
  const int order = q + 1;
  return std::to_string(samples) + " FEM nodes on this face cannot determine a deflection surface of degree " +
         std::to_string(q) + " (" + why + "): it needs at least " + std::to_string(order * order) +
         " nodes with at least " + std::to_string(order) +
         " distinct values of each surface parameter (t and s), not all on one line or curve; lower the "
         "degree or give the face more FEM nodes";
}

void check(std::span<const FieldSample> samples, const ParameterRectangle& domain, const SurfaceFitOptions& options) {
  if (options.degree < 1 || options.degree > kMaxReconstructionDegree) {
    throw InputError("the degree of a deflection surface must be 1 to " + std::to_string(kMaxReconstructionDegree) +
                     ", got " + std::to_string(options.degree));
  }
  if (!(options.smoothing > 0.0) || !std::isfinite(options.smoothing)) {
    throw InputError("the smoothing of a deflection surface must be a finite positive number");
  }
  if (!(options.aspect > 0.0) || !std::isfinite(options.aspect)) {
    throw InputError("the aspect of a face must be a finite positive number");
  }
  const bool finite = std::isfinite(domain.u_first) && std::isfinite(domain.u_last) &&
                      std::isfinite(domain.v_first) && std::isfinite(domain.v_last);
  if (!finite || !(domain.u_first < domain.u_last) || !(domain.v_first < domain.v_last)) {
    throw std::invalid_argument("surface fit: the parameter domain must be a finite, non-empty rectangle");
  }
  for (std::size_t j = 0; j < samples.size(); ++j) {
    if (!is_finite(samples[j].value)) {
      throw InputError("FEM node " + std::to_string(j + 1) + " on this face has a deflection that is not finite");
    }
  }
}

/// The parameters of one direction, clamped into [first, last] (a sample farther outside than
/// the grid tolerance is an error of the caller's projection).
std::vector<double> clamped_parameters(std::span<const FieldSample> samples, double FieldSample::*member,
                                       double first, double last) {
  const double slack = kSameParameter * (last - first);
  std::vector<double> t(samples.size());
  for (std::size_t j = 0; j < samples.size(); ++j) {
    const double value = samples[j].*member;
    if (!(value >= first - slack && value <= last + slack)) {
      throw std::invalid_argument("surface fit: sample " + std::to_string(j) + " lies outside the parameter domain");
    }
    t[j] = std::clamp(value, first, last);
  }
  return t;
}

/// The distinct values of one parameter: sorted values closer than `tolerance` to their
/// neighbour are one level (their mean).
struct Levels {
  std::vector<double> values;          ///< increasing
  std::vector<std::size_t> of_sample;  ///< the level of every sample
  bool sharp = true;                   ///< every level spans at most `tolerance`
};

Levels levels_of(const std::vector<double>& t, double tolerance) {
  std::vector<std::size_t> order(t.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return t[a] < t[b]; });
  Levels levels{.of_sample = std::vector<std::size_t>(t.size())};
  std::size_t begin = 0;  // first position in `order` of the current level
  for (std::size_t k = 0; k < order.size(); ++k) {
    levels.of_sample[order[k]] = levels.values.size();
    const bool closes = k + 1 == order.size() || t[order[k + 1]] - t[order[k]] > tolerance;
    if (!closes) continue;
    double sum = 0.0;
    for (std::size_t i = begin; i <= k; ++i) sum += t[order[i]];
    levels.values.push_back(sum / static_cast<double>(k + 1 - begin));
    levels.sharp = levels.sharp && t[order[k]] - t[order[begin]] <= tolerance;
    begin = k + 1;
  }
  return levels;
}

/// The samples' (u, v) form a grid: enough levels each way and every pair of levels once.
bool is_grid(const Levels& u, const Levels& v, int q) {
  const std::size_t m = u.values.size();
  const std::size_t n = v.values.size();
  const auto order = static_cast<std::size_t>(q) + 1;
  if (!u.sharp || !v.sharp || m < order || n < order || m * n != u.of_sample.size()) return false;
  std::vector<bool> seen(m * n, false);
  for (std::size_t j = 0; j < u.of_sample.size(); ++j) {
    const std::size_t cell = u.of_sample[j] * n + v.of_sample[j];
    if (seen[cell]) return false;
    seen[cell] = true;
  }
  return true;
}

/// The degree-q basis functions on `knots` that are non-zero at t: N_{first + a}(t) = value[a].
struct BasisAt {
  std::size_t first = 0;
  detail::BasisDerivatives n;
  double value(std::size_t a) const { return n[0][a]; }
};

BasisAt basis_at(const std::vector<double>& knots, int q, double t) {
  const std::size_t span = detail::find_span(knots, q, knots.size() - static_cast<std::size_t>(q) - 1, t);
  BasisAt basis{.first = span - static_cast<std::size_t>(q)};
  detail::basis_derivatives(knots, q, span, t, 0, basis.n);
  return basis;
}

SparseMatrix from_triplets(Eigen::Index rows, Eigen::Index cols, const Triplets& entries) {
  SparseMatrix matrix(rows, cols);
  matrix.setFromTriplets(entries.begin(), entries.end());
  return matrix;
}

/// Interpolation knots for parameters t_0 < ... < t_{m-1} inside [first, last]: the averaged
/// interior knots of The NURBS Book eq. (9.8), clamped at the domain's ends rather than at t_0
/// and t_{m-1}. Basis function i is then still positive at t_i (Schoenberg-Whitney: the first
/// one's support [first, knot_{q+1}) holds t_0, the last one's (knot_{m-1}, last] holds
/// t_{m-1}), so the collocation matrix is non-singular; between a domain end and the nearest
/// grid line the field is the end polynomial piece continued.
std::vector<double> interpolation_knots(const std::vector<double>& t, int q, double first, double last) {
  std::vector<double> knots = averaged_knots(t, q);
  const auto order = static_cast<std::ptrdiff_t>(q) + 1;
  std::fill(knots.begin(), knots.begin() + order, first);
  std::fill(knots.end() - order, knots.end(), last);
  return knots;
}

// Global interpolation on a grid (The NURBS Book section 9.2.5): the grid values, one per
// pair of levels, through grid_interpolation.hpp.
SurfaceFit interpolate_grid(const Levels& u, const Levels& v, std::span<const FieldSample> samples,
                            const ParameterRectangle& domain, int q) {
  const std::size_t m = u.values.size();
  const std::size_t n = v.values.size();
  std::vector<double> u_knots = interpolation_knots(u.values, q, domain.u_first, domain.u_last);
  std::vector<double> v_knots = interpolation_knots(v.values, q, domain.v_first, domain.v_last);
  std::vector<Vec3> values(m * n);
  for (std::size_t j = 0; j < samples.size(); ++j) values[u.of_sample[j] * n + v.of_sample[j]] = samples[j].value;
  std::vector<Vec3> poles = detail::interpolate_on_grid(u_knots, q, u.values, v_knots, q, v.values, values);
  SurfaceFitReport report{.method = SurfaceFitMethod::interpolation, .degree = q, .u_poles = m, .v_poles = n};
  return {BSplineSurface(q, q, std::move(u_knots), std::move(v_knots), std::move(poles)), report};
}

/// Clamped knots on [first, last] with `spans` equal spans.
std::vector<double> uniform_knots(double first, double last, int q, std::size_t spans) {
  const auto p = static_cast<std::size_t>(q);
  std::vector<double> knots(spans + 2 * p + 1, last);
  for (std::size_t k = 0; k < spans; ++k) {
    knots[p + k] = first + (last - first) * static_cast<double>(k) / static_cast<double>(spans);
  }
  std::fill(knots.begin(), knots.begin() + static_cast<std::ptrdiff_t>(p), first);
  return knots;
}

/// Row r, r = 0 .. count - q - 2: the jump of the q-th derivative at the interior knot
/// knots[r + q + 1] of the spline with poles c, as weights w_l of c_{r+l}, l = 0 .. q + 1,
/// times h^q / q! (h the span length): the jumps of a net with unit spans. On each span the
/// q-th derivative is a constant, c^(q)_r on span r + q, reached by q differencings
/// (The NURBS Book eq. 3.8):
///     c^(k)_i = (q - k + 1) / (knots[i + q + 1] - knots[i + k]) (c^(k-1)_{i+1} - c^(k-1)_i).
/// For equal spans the rows are the differences of order q + 1 of the poles.
std::vector<std::array<double, kMaxWeights>> jump_rows(const std::vector<double>& knots, int q, double h) {
  const auto p = static_cast<std::size_t>(q);
  const std::size_t count = knots.size() - p - 1;
  double scale = 1.0;
  for (int k = 1; k <= q; ++k) scale *= h / k;
  // derivative(r)[l]: c^(q)_r = sum_l derivative(r)[l] c_{r+l}, l = 0..q.
  const auto derivative = [&](std::size_t r) {
    std::array<std::array<double, kMaxWeights>, kMaxWeights> w{};  // w[s][l], the window of c^(k)_{r+s}
    for (std::size_t s = 0; s <= p; ++s) w[s][0] = 1.0;
    for (std::size_t k = 1; k <= p; ++k) {
      for (std::size_t s = 0; s + k <= p; ++s) {
        const double f = static_cast<double>(p - k + 1) / (knots[r + s + p + 1] - knots[r + s + k]);
        for (std::size_t l = k + 1; l-- > 0;) w[s][l] = f * ((l > 0 ? w[s + 1][l - 1] : 0.0) - w[s][l]);
      }
    }
    return w[0];
  };
  std::vector<std::array<double, kMaxWeights>> rows;
  for (std::size_t r = 0; r + p + 1 < count; ++r) {
    const std::array<double, kMaxWeights> left = derivative(r);
    const std::array<double, kMaxWeights> right = derivative(r + 1);
    std::array<double, kMaxWeights> row{};
    for (std::size_t l = 0; l <= p; ++l) {
      row[l] -= scale * left[l];
      row[l + 1] += scale * right[l];
    }
    rows.push_back(row);
  }
  return rows;
}

/// Knot spans of the least-squares net in u and v. Scaled to the face (u range of length
/// `aspect`, v range of length 1), the samples' bounding box of area A should hold about
/// N / kSamplesPerSpan square spans of side H = sqrt(kSamplesPerSpan A / N), the spacing of the
/// samples; the net keeps that side over the whole domain, but not below the side that gives
/// kMaxPolesPerSample N spans in all.
std::array<std::size_t, 2> span_counts(const std::vector<double>& x, const std::vector<double>& y,
                                        double aspect) {
  const auto [x_low, x_high] = std::minmax_element(x.begin(), x.end());
  const auto [y_low, y_high] = std::minmax_element(y.begin(), y.end());
  const double n = static_cast<double>(x.size());
  const double area = (*x_high - *x_low) * aspect * (*y_high - *y_low);
  const double side = std::max(std::sqrt(kSamplesPerSpan * area / n), std::sqrt(aspect / (kMaxPolesPerSample * n)));
  const auto spans = [&](double length) { return static_cast<std::size_t>(std::max(1.0, std::round(length / side))); };
  return {spans(aspect), spans(1.0)};
}

/// B: the collocation matrix of the samples at (u_j, v_j), B_jk = N_a(u_j) N_b(v_j), k = a n_v + b.
SparseMatrix collocation_matrix(const std::vector<double>& u, const std::vector<double>& v,
                                const std::vector<double>& u_knots, const std::vector<double>& v_knots, int q,
                                std::size_t nv, Eigen::Index poles) {
  const auto p = static_cast<std::size_t>(q);
  Triplets entries;
  for (std::size_t j = 0; j < u.size(); ++j) {
    const BasisAt nu_j = basis_at(u_knots, q, u[j]);
    const BasisAt nv_j = basis_at(v_knots, q, v[j]);
    for (std::size_t a = 0; a <= p; ++a) {
      for (std::size_t b = 0; b <= p; ++b) {
        entries.emplace_back(static_cast<int>(j), static_cast<int>((nu_j.first + a) * nv + nv_j.first + b),
                             nu_j.value(a) * nv_j.value(b));
      }
    }
  }
  return from_triplets(static_cast<Eigen::Index>(u.size()), poles, entries);
}

/// J: the u jumps of every row of poles at fixed b, then the v jumps of every row at fixed a
/// (jump_rows, spans of h_u and h_v).
SparseMatrix jump_matrix(const std::vector<double>& u_knots, const std::vector<double>& v_knots, int q, std::size_t nu,
                         std::size_t nv, double h_u, double h_v, Eigen::Index poles) {
  const auto p = static_cast<std::size_t>(q);
  const auto u_jumps = jump_rows(u_knots, q, h_u);
  const auto v_jumps = jump_rows(v_knots, q, h_v);
  Triplets entries;
  int row = 0;
  for (std::size_t r = 0; r < u_jumps.size(); ++r) {
    for (std::size_t b = 0; b < nv; ++b, ++row) {
      for (std::size_t l = 0; l <= p + 1; ++l) {
        entries.emplace_back(row, static_cast<int>((r + l) * nv + b), u_jumps[r][l]);
      }
    }
  }
  for (std::size_t a = 0; a < nu; ++a) {
    for (std::size_t r = 0; r < v_jumps.size(); ++r, ++row) {
      for (std::size_t l = 0; l <= p + 1; ++l) {
        entries.emplace_back(row, static_cast<int>(a * nv + r + l), v_jumps[r][l]);
      }
    }
  }
  return from_triplets(row, poles, entries);
}

/// The poles c of (B^T B + mu J^T J) c = B^T V, mu = smoothing tr(B^T B) / tr(J^T J), by a
/// sparse LDL^T; throws InputError where a pivot shows the samples leave the field undetermined.
std::vector<Vec3> solve_normal_equations(const SparseMatrix& b_matrix, const SparseMatrix& j_matrix,
                                         std::span<const FieldSample> samples, const SurfaceFitOptions& options) {
  const Eigen::Index poles = b_matrix.cols();
  const SparseMatrix data = b_matrix.transpose() * b_matrix;
  const SparseMatrix penalty = j_matrix.transpose() * j_matrix;
  const double penalty_trace = penalty.diagonal().sum();
  const double mu = penalty_trace > 0.0 ? options.smoothing * data.diagonal().sum() / penalty_trace : 0.0;
  const SparseMatrix normal = data + mu * penalty;
  Eigen::MatrixXd values(static_cast<Eigen::Index>(samples.size()), 3);
  for (std::size_t j = 0; j < samples.size(); ++j) {
    for (int c = 0; c < 3; ++c) values(static_cast<Eigen::Index>(j), c) = samples[j].value[c];
  }
  const Eigen::MatrixXd rhs = b_matrix.transpose() * values;

  const Eigen::SimplicialLDLT<SparseMatrix> ldlt(normal);
  bool singular = ldlt.info() != Eigen::Success;
  if (!singular) {
    // Pivot D_k of the permuted matrix P A P^T against its diagonal entry A_ii, k = P(i).
    const Eigen::VectorXd diagonal = normal.diagonal();
    const auto& permutation = ldlt.permutationP().indices();
    for (Eigen::Index i = 0; i < poles && !singular; ++i) {
      const double pivot = ldlt.vectorD()(permutation(i));
      singular = !(pivot > kSingularPivot * diagonal(i));
    }
  }
  if (singular) {
    throw InputError(cannot_determine(samples.size(), options.degree,
                                      "they lie on one line or curve of the parameter plane, or on too small "
                                      "a part of the domain"));
  }
  const Eigen::MatrixXd solution = ldlt.solve(rhs);
  std::vector<Vec3> pole_values(static_cast<std::size_t>(poles));
  for (std::size_t k = 0; k < pole_values.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    pole_values[k] = {solution(i, 0), solution(i, 1), solution(i, 2)};
  }
  return pole_values;
}


// Regularised least squares on a net of uniform clamped knots. With B the collocation matrix
// of the samples (B_jk = N_a(u_j) N_b(v_j), k = a n_v + b), V the sample values and c the poles,
//     minimise  |B c - V|^2 + mu (|J_u c|^2 + |J_v c|^2),
// where J_u holds, for every row of poles at fixed b, the jumps of the q-th u-derivative across
// the interior u knots (jump_rows, unit spans) and J_v likewise. J c = 0 exactly when d is a
// polynomial of degree <= q in u and in v, so such fields are reproduced whatever mu, and the
// penalty, the P-spline difference penalty of order q + 1 for equal spans, fills knot spans
// without samples with the smoothest continuation. mu = smoothing tr(B^T B) / tr(J^T J) makes
// the two terms comparable for any units and sample count. The normal equations
//     (B^T B + mu J^T J) c = B^T V
// are sparse and positive definite iff no polynomial of degree <= q in u and v other than zero
// vanishes at every sample; a sparse LDL^T solves them for the three components.
SurfaceFit least_squares(const std::vector<double>& u, const std::vector<double>& v,
                         std::span<const FieldSample> samples, const ParameterRectangle& domain,
                         const SurfaceFitOptions& options) {
  const int q = options.degree;
  const auto p = static_cast<std::size_t>(q);
  const double u_length = domain.u_last - domain.u_first;
  const double v_length = domain.v_last - domain.v_first;
  std::vector<double> x(u.size());
  std::vector<double> y(v.size());
  for (std::size_t j = 0; j < u.size(); ++j) {
    x[j] = (u[j] - domain.u_first) / u_length;
    y[j] = (v[j] - domain.v_first) / v_length;
  }
  const auto [u_spans, v_spans] = span_counts(x, y, options.aspect);
  std::vector<double> u_knots = uniform_knots(domain.u_first, domain.u_last, q, u_spans);
  std::vector<double> v_knots = uniform_knots(domain.v_first, domain.v_last, q, v_spans);
  const std::size_t nu = u_spans + p;
  const std::size_t nv = v_spans + p;
  const auto poles = static_cast<Eigen::Index>(nu * nv);

  const SparseMatrix b_matrix = collocation_matrix(u, v, u_knots, v_knots, q, nv, poles);
  const SparseMatrix j_matrix = jump_matrix(u_knots, v_knots, q, nu, nv, u_length / static_cast<double>(u_spans),
                                            v_length / static_cast<double>(v_spans), poles);
  std::vector<Vec3> pole_values = solve_normal_equations(b_matrix, j_matrix, samples, options);
  SurfaceFitReport report{.method = SurfaceFitMethod::least_squares, .degree = q, .u_poles = nu, .v_poles = nv};
  return {BSplineSurface(q, q, std::move(u_knots), std::move(v_knots), std::move(pole_values)), report};
}


void fill_residuals(SurfaceFit& fit, std::span<const FieldSample> samples, const std::vector<double>& u,
                    const std::vector<double>& v) {
  double sum = 0.0;
  for (std::size_t j = 0; j < samples.size(); ++j) {
    const double r = distance(fit.field.point(u[j], v[j]), samples[j].value);
    fit.report.max_residual = std::max(fit.report.max_residual, r);
    sum += r * r;
  }
  fit.report.samples = samples.size();
  fit.report.rms_residual = std::sqrt(sum / static_cast<double>(samples.size()));
}

}  // namespace

double face_aspect(const BSplineSurface& face) {
  const ParameterRectangle r = face.domain();
  double along_u = 0.0, along_v = 0.0;
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) {
      const double u = r.u_first + (r.u_last - r.u_first) * (i + 0.5) / 5.0;
      const double v = r.v_first + (r.v_last - r.v_first) * (j + 0.5) / 5.0;
      const SurfaceDerivatives d = face.derivatives(u, v);
      along_u += norm(d.du) * (r.u_last - r.u_first);
      along_v += norm(d.dv) * (r.v_last - r.v_first);
    }
  }
  if (!(along_u > 0.0) || !(along_v > 0.0)) return 1.0;  // degenerate face: no preference
  return std::clamp(along_u / along_v, 1e-6, 1e6);
}

SurfaceFit fit_surface_field(std::span<const FieldSample> samples, const ParameterRectangle& domain,
                             const SurfaceFitOptions& options) {
  check(samples, domain, options);
  const std::vector<double> u = clamped_parameters(samples, &FieldSample::u, domain.u_first, domain.u_last);
  const std::vector<double> v = clamped_parameters(samples, &FieldSample::v, domain.v_first, domain.v_last);
  const Levels u_levels = levels_of(u, kSameParameter * (domain.u_last - domain.u_first));
  const Levels v_levels = levels_of(v, kSameParameter * (domain.v_last - domain.v_first));
  const int q = options.degree;
  const auto order = static_cast<std::size_t>(q) + 1;
  SurfaceFit fit = [&] {
    if (is_grid(u_levels, v_levels, q)) return interpolate_grid(u_levels, v_levels, samples, domain, q);
    if (samples.size() < order * order) {
      throw InputError(cannot_determine(samples.size(), q, "too few nodes"));
    }
    for (const auto& [levels, name] : {std::pair{&u_levels, "t"}, std::pair{&v_levels, "s"}}) {
      if (levels->values.size() < order) {
        throw InputError(cannot_determine(samples.size(), q,
                                          "they have only " + std::to_string(levels->values.size()) +
                                              " distinct values of " + name));
      }
    }
    return least_squares(u, v, samples, domain, options);
  }();
  fill_residuals(fit, samples, u, v);
  return fit;
}

}  // namespace hotmesh::geometry
