// Tests of the PCG solver: convergence on SPD systems to the exact solution, honest reports
// of non-convergence and breakdown, and the projection hook.
#include <gtest/gtest.h>

#include <cmath>

#include "hotmesh/deform/pcg.hpp"

namespace hotmesh::deform {
namespace {

/// The 1D Laplacian with Dirichlet ends, scaled row i by (1 + i) to make Jacobi matter:
/// A = S L S with S = diag(sqrt(1 + i)), SPD.
class ScaledLaplacian final : public LinearOperator {
 public:
  explicit ScaledLaplacian(std::size_t n, double shift = 0.0) : n_(n), shift_(shift) {}
  std::size_t size() const override { return n_; }
  void apply(std::span<const double> x, std::span<double> y) const override {
    for (std::size_t i = 0; i < n_; ++i) {
      const double si = s(i);
      double v = 2.0 * si * x[i];
      if (i > 0) v -= s(i - 1) * x[i - 1];
      if (i + 1 < n_) v -= s(i + 1) * x[i + 1];
      y[i] = si * v - shift_ * x[i];
    }
  }
  double diagonal(std::size_t i) const { return 2.0 * s(i) * s(i) - shift_; }

 private:
  static double s(std::size_t i) { return std::sqrt(1.0 + static_cast<double>(i)); }
  std::size_t n_;
  double shift_;
};

class Identity final : public LinearOperator {
 public:
  explicit Identity(std::size_t n) : n_(n) {}
  std::size_t size() const override { return n_; }
  void apply(std::span<const double> x, std::span<double> y) const override { std::copy(x.begin(), x.end(), y.begin()); }

 private:
  std::size_t n_;
};

class Jacobi final : public LinearOperator {
 public:
  explicit Jacobi(const ScaledLaplacian& a) : a_(a) {}
  std::size_t size() const override { return a_.size(); }
  void apply(std::span<const double> x, std::span<double> y) const override {
    for (std::size_t i = 0; i < x.size(); ++i) y[i] = x[i] / a_.diagonal(i);
  }

 private:
  const ScaledLaplacian& a_;
};

TEST(Pcg, SolvesSpdSystemToTolerance) {
  const std::size_t n = 200;
  const ScaledLaplacian a(n);
  std::vector<double> exact(n), b(n), x(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) exact[i] = std::sin(0.05 * static_cast<double>(i)) + 0.01 * static_cast<double>(i);
  a.apply(exact, b);
  const PcgResult r = pcg(a, Jacobi(a), b, x, {.relative_tolerance = 1e-12, .max_iterations = 1000});
  EXPECT_TRUE(r.converged);
  EXPECT_FALSE(r.breakdown);
  EXPECT_LE(r.iterations, static_cast<int>(n));
  EXPECT_LE(r.final_residual, 1e-12 * r.initial_residual);
  ASSERT_EQ(r.history.size(), static_cast<std::size_t>(r.iterations) + 1);
  EXPECT_EQ(r.history.front(), 1.0);
  double error = 0.0;
  for (std::size_t i = 0; i < n; ++i) error = std::max(error, std::abs(x[i] - exact[i]));
  EXPECT_LT(error, 1e-7);
}

TEST(Pcg, JacobiBeatsNoPreconditionerOnBadlyScaledSystem) {
  const std::size_t n = 300;
  const ScaledLaplacian a(n);
  std::vector<double> b(n, 1.0), x1(n, 0.0), x2(n, 0.0);
  const auto plain = pcg(a, Identity(n), b, x1, {.relative_tolerance = 1e-8, .max_iterations = 5000});
  const auto jacobi = pcg(a, Jacobi(a), b, x2, {.relative_tolerance = 1e-8, .max_iterations = 5000});
  EXPECT_TRUE(plain.converged);
  EXPECT_TRUE(jacobi.converged);
  EXPECT_LT(jacobi.iterations, plain.iterations);
}

TEST(Pcg, ReportsNonConvergenceHonestly) {
  const std::size_t n = 100;
  const ScaledLaplacian a(n);
  std::vector<double> b(n, 1.0), x(n, 0.0);
  const PcgResult r = pcg(a, Jacobi(a), b, x, {.relative_tolerance = 1e-12, .max_iterations = 5});
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.iterations, 5);
  EXPECT_GT(r.final_residual, 1e-12 * r.initial_residual);
}

TEST(Pcg, ReportsBreakdownOnIndefiniteSystem) {
  const std::size_t n = 50;
  const ScaledLaplacian a(n, 30.0);  // shifted far below zero: indefinite
  std::vector<double> b(n, 1.0), x(n, 0.0);
  const PcgResult r = pcg(a, Identity(n), b, x, {.relative_tolerance = 1e-10, .max_iterations = 500});
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(r.breakdown);
}

TEST(Pcg, ZeroRightHandSideConvergesAtOnce) {
  const ScaledLaplacian a(10);
  std::vector<double> b(10, 0.0), x(10, 0.0);
  const PcgResult r = pcg(a, Identity(10), b, x);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.iterations, 0);
}

TEST(Pcg, ProjectionHookKeepsIteratesInSubspace) {
  // Solve on the subspace x_0 = 0 with the operator projected P A P.
  const std::size_t n = 40;
  const ScaledLaplacian a(n);
  struct Projected final : LinearOperator {
    const LinearOperator& a;
    explicit Projected(const LinearOperator& op) : a(op) {}
    std::size_t size() const override { return a.size(); }
    void apply(std::span<const double> x, std::span<double> y) const override {
      a.apply(x, y);
      y[0] = 0.0;
    }
  } projected(a);
  std::vector<double> b(n, 1.0), x(n, 0.0);
  const PcgResult r = pcg(projected, Identity(n), b, x,
                          {.relative_tolerance = 1e-10, .project = [](std::span<double> v) { v[0] = 0.0; }});
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(x[0], 0.0);
}

}  // namespace
}  // namespace hotmesh::deform
