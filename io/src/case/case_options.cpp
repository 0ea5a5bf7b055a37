// hotmesh io: the case file's solver, material, quality and pictures sections
// (case_parser.hpp).
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <stdexcept>
#include <system_error>
#include <type_traits>
#include <utility>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/geometry/reconstruction.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/deflection_csv.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "case/case_parser.hpp"

namespace hotmesh::io::detail {

namespace {

constexpr std::array<std::string_view, 4> kQualityKeys{"min_scaled_jacobian", "max_non_orthogonality", "max_skewness",
                                                      "smoothing"};
constexpr std::array<std::string_view, 12> kSolverKeys{
    "increments", "newton_tolerance", "max_newton_iterations", "pcg_tolerance", "max_pcg_iterations", "threads",
    "max_increment_splits", "linear", "amg", "amg_reuse", "forcing", "predictor"};
constexpr std::array<std::string_view, 5> kMaterialKeys{"law", "alpha_s", "alpha_v", "drop_jacobian",
                                                        "wall_distance_exponent"};

}  // namespace

void CaseParser::read_solver(const Entry& e) {
  if (!reader_.map_or_empty(e, cat("a map of solver options (", join(kSolverKeys), ")"))) return;
  const MapEntries m = reader_.keys(e, kSolverKeys);
  const auto integer = [&](std::string_view key, int& field, int low) {
    if (const Entry* x = m.find(key)) field = reader_.integer_in(*x, low).value_or(field);
  };
  // Relative tolerances: below about 1e-14 double precision cannot reach them, and the
  // solvers would iterate on rounding until their limit.
  const auto fraction = [&](std::string_view key, double& field) {
    const auto reachable = [](double v) { return v >= 1e-14 && v < 1.0; };
    if (const Entry* x = m.find(key)) {
      field = reader_.number_where(*x, reachable, "at least 1e-14 (what double precision reaches) and below 1")
                  .value_or(field);
    }
  };
  deform::SolverOptions& s = c_.solver;
  if (const Entry* x = m.find("increments")) {
    const auto n = x->value.IsScalar() && !quoted(x->value) ? detail::parse<std::int64_t>(x->value.Scalar()) : std::nullopt;
    if (n && *n > kMaxIncrements) {
      reader_.error(*x, cat("must be at most ", std::to_string(kMaxIncrements), ", got ", x->value.Scalar(),
                            ": the paper's cases take 16, and an increment too large for the mesh is halved by "
                            "the solver itself (max_increment_splits), so tens of increments are enough"));
    } else {
      s.increments = reader_.integer_in(*x, 1).value_or(s.increments);
    }
  }
  fraction("newton_tolerance", s.newton_tolerance);
  integer("max_newton_iterations", s.max_newton_iterations, 1);
  fraction("pcg_tolerance", s.pcg_tolerance);
  integer("max_pcg_iterations", s.max_pcg_iterations, 1);
  integer("threads", c_.threads, 0);
  if (const Entry* x = m.find("max_increment_splits")) {
    s.max_increment_splits = reader_.integer_in(*x, 0, kMaxIncrementSplits).value_or(s.max_increment_splits);
  }
  if (const Entry* x = m.find("linear")) {
    if (const auto k = reader_.choice(*x, deform::kLinearSolverNames)) s.linear = *k;
  }
  if (const Entry* x = m.find("amg")) {
    if (const auto k = reader_.choice(*x, deform::kAmgPackageNames)) s.amg = *k;
  }
  if (const Entry* x = m.find("amg_reuse")) {
    if (const auto k = reader_.choice(*x, deform::kAmgReuseNames)) {
      if (*k == deform::AmgReuse::interpolation && s.amg == deform::AmgPackage::hypre) {
        reader_.error(*x, "interpolation is kept by amg: gamg only; with hypre choose preconditioner or none");
      } else {
        s.amg_reuse = *k;
      }
    }
  }
  if (const Entry* x = m.find("forcing")) {
    if (const auto k = reader_.choice(*x, deform::kForcingTermNames)) s.forcing = *k;
  }
  if (const Entry* x = m.find("predictor")) s.predictor = reader_.boolean(*x).value_or(s.predictor);
}

void CaseParser::read_material(const Entry& e) {
  if (!reader_.map_or_empty(e, cat("a map of material options (", join(kMaterialKeys), ")"))) return;
  const MapEntries m = reader_.keys(e, kMaterialKeys);
  deform::MaterialOptions& mat = c_.material;
  if (const Entry* x = m.find("law")) {
    if (const auto law = reader_.choice(*x, deform::kStiffnessLawNames)) mat.law = *law;
  }
  if (const Entry* x = m.find("drop_jacobian")) mat.drop_jacobian = reader_.boolean(*x).value_or(mat.drop_jacobian);
  if (const Entry* x = m.find("alpha_s")) {
    mat.alpha_s = reader_.number_where(*x, [](double v) { return v > 0.0; }, "> 0").value_or(mat.alpha_s);
  }
  if (const Entry* x = m.find("alpha_v")) {
    mat.alpha_v = reader_.number_where(*x, [](double v) { return v >= 0.0; }, ">= 0").value_or(mat.alpha_v);
  }
  if (const Entry* x = m.find("wall_distance_exponent")) {
    mat.wall_distance_exponent =
        reader_.number_where(*x, [](double v) { return v >= 0.0 && v <= 4.0; }, "from 0 to 4")
            .value_or(mat.wall_distance_exponent);
  }
}

/// The limits every increment's cells keep and the quality step (deform::QualityLimits).
void CaseParser::read_quality(const Entry& e) {
  if (!reader_.map_or_empty(e, cat("a map of quality limits (", join(kQualityKeys), ")"))) return;
  const MapEntries m = reader_.keys(e, kQualityKeys);
  deform::QualityLimits& q = c_.solver.quality;
  if (const Entry* x = m.find("min_scaled_jacobian")) {
    q.min_scaled_jacobian =
        reader_.number_where(*x, [](double v) { return v > 0.0 && v < 1.0; }, "above 0 and below 1 (the ideal cell's)")
            .value_or(q.min_scaled_jacobian);
  }
  if (const Entry* x = m.find("max_non_orthogonality")) {
    q.max_non_orthogonality =
        reader_.number_where(*x, [](double v) { return v > 0.0 && v < 90.0; }, "degrees above 0 and below 90")
            .value_or(q.max_non_orthogonality);
  }
  if (const Entry* x = m.find("max_skewness")) {
    q.max_skewness = reader_.number_where(*x, [](double v) { return v > 0.0; }, "> 0").value_or(q.max_skewness);
  }
  if (const Entry* x = m.find("smoothing")) q.smoothing = reader_.boolean(*x).value_or(q.smoothing);
}

void CaseParser::read_pictures(const Entry& e) {
  if (!reader_.map_or_empty(e, "a map of picture names to views [xmin, xmax, ymin, ymax]")) return;
  for (const Entry& view : reader_.keys(e, {}).entries) {
    const bool plain = std::all_of(view.name.begin(), view.name.end(), [](char ch) {
      return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-';
    });
    if (!plain) {
      reader_.error(view, "picture names become file names: use letters, digits, '_' and '-'");
      continue;
    }
    if (!view.value.IsSequence() || view.value.size() != 4) {
      reader_.error(view, "expected a view [xmin, xmax, ymin, ymax], got " + describe(view.value));
      continue;
    }
    std::array<double, 4> v{};
    bool ok = true;
    for (std::size_t i = 0; i < 4 && ok; ++i) {
      const auto value = reader_.number(view.item(i));
      ok = value.has_value();
      v[i] = value.value_or(0.0);
    }
    if (!ok) continue;
    if (!(v[0] < v[1] && v[2] < v[3])) {
      reader_.error(view, "the view needs xmin < xmax and ymin < ymax");
      continue;
    }
    c_.pictures.push_back({view.name, v[0], v[1], v[2], v[3], view.line});
  }
}

}  // namespace hotmesh::io::detail
