// hotmesh geometry (internal): deflection fields joined along shared edges (field_joins.hpp).
#include "reconstruct/field_joins.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "spline/bspline_basis.hpp"

namespace hotmesh::geometry::detail {
namespace {

bool along_u(int side) { return side < 2; }

/// A field's knots, poles and degrees, to be changed and put together again.
struct FieldParts {
  int p_u, p_v;
  std::vector<double> u_knots, v_knots;
  std::vector<Vec3> poles;  ///< u-major: poles[i * v_count() + j]

  explicit FieldParts(const BSplineSurface& f)
      : p_u(f.u_degree()), p_v(f.v_degree()), u_knots(f.u_knots()), v_knots(f.v_knots()), poles(f.poles()) {}
  std::size_t u_count() const { return u_knots.size() - static_cast<std::size_t>(p_u) - 1; }
  std::size_t v_count() const { return v_knots.size() - static_cast<std::size_t>(p_v) - 1; }
  BSplineSurface surface() const { return {p_u, p_v, u_knots, v_knots, poles}; }

  const std::vector<double>& knots(bool u) const { return u ? u_knots : v_knots; }
  int degree(bool u) const { return u ? p_u : p_v; }
  double first(bool u) const { return knots(u)[static_cast<std::size_t>(degree(u))]; }
  double last(bool u) const { return knots(u)[knots(u).size() - static_cast<std::size_t>(degree(u)) - 1]; }
  /// How many poles a side has, and where its k-th one (in the order of increasing parameter)
  /// is in `poles`.
  std::size_t side_count(int side) const { return along_u(side) ? u_count() : v_count(); }
  std::size_t side_index(int side, std::size_t k) const {
    if (along_u(side)) return k * v_count() + (side == 0 ? 0 : v_count() - 1);
    return (side == 2 ? 0 : u_count() - 1) * v_count() + k;
  }
  /// The poles along a side, in the order of increasing parameter: row or column k.
  std::vector<Vec3*> side_poles(int side) {
    std::vector<Vec3*> out;
    for (std::size_t k = 0; k < side_count(side); ++k) out.push_back(&poles[side_index(side, k)]);
    return out;
  }
  /// The field along a side at parameter x (u along sides 0 and 1, v along 2 and 3): the
  /// B-spline curve of that side's poles, sum_k N_k(x) P_k.
  Vec3 on_side(int side, double x) const {
    const bool u = along_u(side);
    const std::size_t span = find_span(knots(u), degree(u), side_count(side), x);
    BasisDerivatives n{};
    basis_derivatives(knots(u), degree(u), span, x, 0, n);
    Vec3 sum{};
    const auto p = static_cast<std::size_t>(degree(u));
    for (std::size_t j = 0; j <= p; ++j) sum = sum + n[0][j] * poles[side_index(side, span - p + j)];
    return sum;
  }
  Vec3& corner(int c) {
    const std::size_t i = (c % 2 == 0) ? 0 : u_count() - 1, j = c < 2 ? 0 : v_count() - 1;
    return poles[i * v_count() + j];
  }

  /// Inserts knot x once along u or v (Boehm's algorithm on every line of poles that way).
  void insert(bool u, double x) {
    std::vector<double>& knots = u ? u_knots : v_knots;
    const auto p = static_cast<std::size_t>(degree(u));
    const auto k = static_cast<std::size_t>(std::upper_bound(knots.begin(), knots.end(), x) - knots.begin()) - 1;
    const std::size_t nu = u_count(), nv = v_count();
    const std::size_t n = u ? nu : nv, lines = u ? nv : nu;
    std::vector<Vec3> result((u ? nu + 1 : nu) * (u ? nv : nv + 1));
    const auto at = [&](std::vector<Vec3>& poles_of, std::size_t count_v, std::size_t line, std::size_t i) -> Vec3& {
      return u ? poles_of[i * count_v + line] : poles_of[line * count_v + i];
    };
    const std::size_t new_nv = u ? nv : nv + 1;
    for (std::size_t line = 0; line < lines; ++line) {
      for (std::size_t i = 0; i <= n; ++i) {
        Vec3 value;
        if (i + p <= k) {
          value = at(poles, nv, line, i);
        } else if (i > k) {
          value = at(poles, nv, line, i - 1);
        } else {
          const double alpha = (x - knots[i]) / (knots[i + p] - knots[i]);
          value = alpha * at(poles, nv, line, i) + (1.0 - alpha) * at(poles, nv, line, i - 1);
        }
        at(result, new_nv, line, i) = value;
      }
    }
    knots.insert(knots.begin() + static_cast<std::ptrdiff_t>(k + 1), x);
    poles = std::move(result);
  }
};

/// The distinct interior knots and their multiplicities.
std::vector<std::pair<double, int>> interior_knots(const std::vector<double>& knots, int degree) {
  std::vector<std::pair<double, int>> out;
  const auto first = static_cast<std::size_t>(degree) + 1, last = knots.size() - static_cast<std::size_t>(degree) - 1;
  for (std::size_t i = first; i < last; ++i) {
    if (!out.empty() && out.back().first == knots[i]) {
      ++out.back().second;
    } else {
      out.emplace_back(knots[i], 1);
    }
  }
  return out;
}

/// Inserts knot x into `to` along u or v until it has multiplicity `count` there; a knot
/// within rounding of one `to` has (1e-10 of the range) counts as it. Returns whether it
/// inserted any.
bool insert_knot(FieldParts& to, bool u, double x, int count) {
  const double snap = 1e-10 * (to.last(u) - to.first(u));
  if (x <= to.first(u) + snap || x >= to.last(u) - snap) return false;
  int have = 0;
  for (const auto& [there, m] : interior_knots(to.knots(u), to.degree(u))) {
    if (std::abs(there - x) <= snap) {
      x = there;
      have = m;
    }
  }
  bool inserted = false;
  for (int m = have; m < std::min(count, to.degree(u)); ++m) {
    to.insert(u, x);
    inserted = true;
  }
  return inserted;
}

/// Inserts into `to` (along `u_to`) the knots `from` has along its side, mapped affinely
/// from one parameter range to the other (reversed: end to start). Returns whether it
/// inserted any.
bool take_knots(const FieldParts& from, bool u_from, FieldParts& to, bool u_to, bool reversed) {
  const double f0 = from.first(u_from), f1 = from.last(u_from);
  bool inserted = false;
  for (const auto& [value, count] : interior_knots(from.knots(u_from), from.degree(u_from))) {
    double fraction = (value - f0) / (f1 - f0);
    if (reversed) fraction = 1.0 - fraction;
    inserted |= insert_knot(to, u_to, to.first(u_to) + fraction * (to.last(u_to) - to.first(u_to)), count);
  }
  return inserted;
}

/// Step 1: the same knots along every affine edge. A field's knots along one direction serve
/// all its sides that way, so insertions travel from face to face until none is needed.
void share_affine_knots(std::vector<FieldParts>& parts, std::span<const SharedSide> sides) {
  constexpr int kMaxPasses = 32;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    bool inserted = false;
    for (const SharedSide& s : sides) {
      const bool ua = along_u(s.a.side), ub = along_u(s.b.side);
      inserted |= take_knots(parts[s.a.face], ua, parts[s.b.face], ub, s.reversed);
      inserted |= take_knots(parts[s.b.face], ub, parts[s.a.face], ua, s.reversed);
    }
    if (!inserted) break;
  }
}

/// Step 2: the mean of the two rows of poles along each affine edge (corners apart). Returns
/// the sides whose rows differ in length (the insertions did not settle).
std::vector<SharedSide> average_affine_rows(std::vector<FieldParts>& parts, std::span<const SharedSide> sides) {
  std::vector<SharedSide> unsettled;
  for (const SharedSide& s : sides) {
    auto row_a = parts[s.a.face].side_poles(s.a.side);
    auto row_b = parts[s.b.face].side_poles(s.b.side);
    if (row_a.size() != row_b.size()) {
      unsettled.push_back(s);
      continue;
    }
    if (s.reversed) std::reverse(row_b.begin(), row_b.end());
    for (std::size_t i = 1; i + 1 < row_a.size(); ++i) {
      const Vec3 mean = 0.5 * (*row_a[i] + *row_b[i]);
      *row_a[i] = mean;
      *row_b[i] = mean;
    }
  }
  return unsettled;
}

/// Every field's corner pole at a corner point replaced by their mean.
void mean_corners(std::vector<FieldParts>& parts, std::span<const std::vector<FaceCorner>> corners) {
  for (const std::vector<FaceCorner>& group : corners) {
    if (group.empty()) continue;
    Vec3 sum{};
    for (const FaceCorner& c : group) sum = sum + parts[c.face].corner(c.corner);
    const Vec3 mean = (1.0 / static_cast<double>(group.size())) * sum;
    for (const FaceCorner& c : group) parts[c.face].corner(c.corner) = mean;
  }
}

/// Step 3: each field of an uneven edge takes the images of the other's knots along it (those
/// of b's within a's part of b's side). Where a's side ends inside b's (a T-junction), the
/// target may turn a corner: b takes a knot of full multiplicity there.
void exchange_knots(std::vector<FieldParts>& parts, const UnevenSide& s) {
  const bool ua = along_u(s.a.side), ub = along_u(s.b.side);
  const FieldParts a = parts[s.a.face], b = parts[s.b.face];  // the knots before either takes any
  const double y_first = s.to_b(a.first(ua)), y_last = s.to_b(a.last(ua));
  const double y0 = std::min(y_first, y_last), y1 = std::max(y_first, y_last);
  for (const double y : {y0, y1}) insert_knot(parts[s.b.face], ub, y, b.degree(ub));  // none at b's ends
  for (const auto& [x, count] : interior_knots(a.knots(ua), a.degree(ua))) {
    insert_knot(parts[s.b.face], ub, s.to_b(x), count);
  }
  for (const auto& [y, count] : interior_knots(b.knots(ub), b.degree(ub))) {
    if (y > y0 && y < y1) insert_knot(parts[s.a.face], ua, s.to_a(y), count);
  }
}

/// A point of an uneven edge: a's and b's parameters along their sides there.
struct EdgePoint {
  double a = 0.0;
  double b = 0.0;
};

/// Where the fields of an uneven edge are compared and fitted: 8 points per knot span of a's
/// side, and of b's within a's part of it, each with its image on the other side.
std::vector<EdgePoint> edge_points(const std::vector<FieldParts>& parts, const UnevenSide& s) {
  constexpr int kPerSpan = 8;
  const bool ua = along_u(s.a.side), ub = along_u(s.b.side);
  const FieldParts &a = parts[s.a.face], &b = parts[s.b.face];
  std::vector<EdgePoint> out;
  const auto each_point = [&](const FieldParts& f, bool u, double lo, double hi, auto&& add) {
    std::vector<double> breaks{f.first(u)};
    for (const auto& [knot, count] : interior_knots(f.knots(u), f.degree(u))) breaks.push_back(knot);
    breaks.push_back(f.last(u));
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
      const double x0 = std::max(breaks[k], lo), x1 = std::min(breaks[k + 1], hi);
      if (x1 <= x0) continue;
      for (int i = 0; i < kPerSpan; ++i) add(x0 + (x1 - x0) * i / kPerSpan);
    }
    add(hi);
  };
  each_point(a, ua, a.first(ua), a.last(ua), [&](double x) { out.push_back({x, s.to_b(x)}); });
  const double y0 = std::min(out.front().b, out.back().b), y1 = std::max(out.front().b, out.back().b);
  each_point(b, ub, y0, y1, [&](double y) { out.push_back({s.to_a(y), y}); });
  return out;
}

/// |d_a - d_b| at each point of an uneven edge.
std::vector<double> pointwise_gaps(const std::vector<FieldParts>& parts, const UnevenSide& s,
                                   std::span<const EdgePoint> points) {
  std::vector<double> out;
  for (const EdgePoint& p : points) {
    out.push_back(distance(parts[s.a.face].on_side(s.a.side, p.a), parts[s.b.face].on_side(s.b.side, p.b)));
  }
  return out;
}

/// Step 4's targets on both sides of an uneven edge, as changes of the fields `parts` there.
/// From the fields `before_corners` (before the corner poles took their means, which would put a bump
/// one knot span wide into each, not a spline in the other's parameter), with the fraction
/// f of the way along a's side,
///     m(x) = (d_a(x) + d_b(phi(x))) / 2 + (1 - f) e_0 + f e_1,
/// where e_0, e_1 take m to a's corner poles at the ends of its side: a smooth target that
/// meets the corners the other faces there share.
void add_targets(const std::vector<FieldParts>& before_corners, const std::vector<FieldParts>& parts, const UnevenSide& s,
                 std::span<const EdgePoint> points, std::map<std::pair<std::size_t, int>, std::vector<SideTarget>>& targets) {
  const bool ua = along_u(s.a.side);
  const double x0 = parts[s.a.face].first(ua), x1 = parts[s.a.face].last(ua);
  const auto mean = [&](double x, double y) {
    return 0.5 * (before_corners[s.a.face].on_side(s.a.side, x) + before_corners[s.b.face].on_side(s.b.side, y));
  };
  const Vec3 e0 = parts[s.a.face].on_side(s.a.side, x0) - mean(x0, s.to_b(x0));
  const Vec3 e1 = parts[s.a.face].on_side(s.a.side, x1) - mean(x1, s.to_b(x1));
  for (const EdgePoint& p : points) {
    const double f = (p.a - x0) / (x1 - x0);
    const Vec3 m = mean(p.a, p.b) + (1.0 - f) * e0 + f * e1;
    targets[{s.a.face, s.a.side}].push_back({p.a, m - parts[s.a.face].on_side(s.a.side, p.a)});
    targets[{s.b.face, s.b.side}].push_back({p.b, m - parts[s.b.face].on_side(s.b.side, p.b)});
  }
}

/// The change of a side's row of poles, corners kept (or not), that fits the targets by least
/// squares: min |N dP - r|^2 + mu |dP|^2 over the poles that move, with N_ki = N_i(x_k) and mu
/// 1e-12 of the mean |N_i|^2, which keeps poles the targets barely reach (a side covered in
/// part) where they were and leaves the others' fit as it is. The normal equations
/// (N^T N + mu I) dP = N^T r are banded (half-width q): a sparse LDL^T.
void fit_side(FieldParts& f, int side, std::span<const SideTarget> targets, bool keep_corners = true) {
  const std::size_t n = f.side_count(side);
  const std::size_t kept = keep_corners ? 1 : 0;  // poles kept at each end
  if (n <= 2 * kept || targets.empty()) return;
  const bool u = along_u(side);
  const auto p = static_cast<std::size_t>(f.degree(u));
  const auto inner = static_cast<Eigen::Index>(n - 2 * kept);
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(inner, 3);
  double trace = 0.0;
  for (const SideTarget& t : targets) {
    const std::size_t span = find_span(f.knots(u), f.degree(u), n, t.x);
    BasisDerivatives basis{};
    basis_derivatives(f.knots(u), f.degree(u), span, t.x, 0, basis);
    for (std::size_t j = 0; j <= p; ++j) {
      const std::size_t i = span - p + j;
      if (i < kept || i + kept >= n) continue;  // a corner pole: kept
      const auto row = static_cast<Eigen::Index>(i - kept);
      rhs.row(row) += basis[0][j] * Eigen::RowVector3d(t.change.x, t.change.y, t.change.z);
      trace += basis[0][j] * basis[0][j];
      for (std::size_t l = 0; l <= p; ++l) {
        const std::size_t k = span - p + l;
        if (k >= kept && k + kept < n) entries.emplace_back(row, static_cast<Eigen::Index>(k - kept), basis[0][j] * basis[0][l]);
      }
    }
  }
  if (!(trace > 0.0)) return;  // no target reaches an inner pole
  const double mu = 1e-12 * trace / static_cast<double>(inner);
  for (Eigen::Index i = 0; i < inner; ++i) entries.emplace_back(i, i, mu);
  Eigen::SparseMatrix<double> normal(inner, inner);
  normal.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(normal);
  if (ldlt.info() != Eigen::Success) return;
  const Eigen::MatrixXd change = ldlt.solve(rhs);
  for (Eigen::Index i = 0; i < inner; ++i) {
    f.poles[f.side_index(side, static_cast<std::size_t>(i) + kept)] += Vec3{change(i, 0), change(i, 1), change(i, 2)};
  }
}

/// Step 5: the knot spans of a's side where the fields differ by more than a tenth of the
/// tolerance halved (halving a span cuts the fit's error there about 16-fold for cubics, its
/// neighbours', coupled to it through the fit, less), in `refined` (the fields before joining)
/// at their middle x and at phi(x) on b's side, so both keep the same breaks along the edge.
/// Returns whether it inserted any.
bool halve_spans(std::vector<FieldParts>& refined, const UnevenSide& s, std::span<const EdgePoint> points,
                 std::span<const double> gaps, double tolerance) {
  const bool ua = along_u(s.a.side), ub = along_u(s.b.side);
  const FieldParts& a = refined[s.a.face];
  std::set<double> middles;
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (gaps[k] <= 0.1 * tolerance) continue;
    const std::size_t span = find_span(a.knots(ua), a.degree(ua), a.side_count(s.a.side), points[k].a);
    middles.insert(0.5 * (a.knots(ua)[span] + a.knots(ua)[span + 1]));
  }
  bool inserted = false;
  for (const double x : middles) {
    inserted |= insert_knot(refined[s.a.face], ua, x, 1);
    inserted |= insert_knot(refined[s.b.face], ub, s.to_b(x), 1);
  }
  return inserted;
}

}  // namespace

void fit_side_row(BSplineSurface& field, int side, std::span<const SideTarget> targets, bool keep_corners) {
  FieldParts parts(field);
  fit_side(parts, side, targets, keep_corners);
  field = parts.surface();
}

bool insert_knot(BSplineSurface& field, bool u, double x) {
  FieldParts parts(field);
  if (!insert_knot(parts, u, x, 1)) return false;
  field = parts.surface();
  return true;
}

JoinOutcome join_fields(std::vector<BSplineSurface>& fields, std::span<const SharedSide> sides,
                        std::span<const UnevenSide> uneven, std::span<const std::vector<FaceCorner>> corners,
                        double tolerance) {
  std::vector<FieldParts> refined;  // the fields as fitted, knots inserted (steps 3 and 5)
  refined.reserve(fields.size());
  for (const BSplineSurface& f : fields) refined.emplace_back(f);
  JoinOutcome out;
  std::vector<SharedSide> affine;
  for (const SharedSide& s : sides) {
    const bool ua = along_u(s.a.side), ub = along_u(s.b.side);
    (refined[s.a.face].degree(ua) == refined[s.b.face].degree(ub) ? affine : out.left).push_back(s);
  }
  const std::size_t unequal_degrees = out.left.size();
  // Step 3 for the uneven edges whose fields do not meet already (a field that does, as one
  // polynomial of degree <= q in both faces' parameters, keeps its knots).
  for (const UnevenSide& s : uneven) {
    const std::vector<double> gaps = pointwise_gaps(refined, s, edge_points(refined, s));
    if (*std::max_element(gaps.begin(), gaps.end()) > tolerance) exchange_knots(refined, s);
  }
  // Steps 1, 2 and 4 on the refined fields, then step 5 where the uneven edges' fields do not
  // meet yet: the knots halving inserts reach the faces' affine edges through step 1.
  std::vector<FieldParts> parts;
  for (int halvings = 0;; ++halvings) {
    parts = refined;
    share_affine_knots(parts, affine);
    out.left.resize(unequal_degrees);
    for (const SharedSide& s : average_affine_rows(parts, affine)) out.left.push_back(s);
    const std::vector<FieldParts> before_corners = parts;
    mean_corners(parts, corners);
    std::vector<std::vector<EdgePoint>> points;
    std::map<std::pair<std::size_t, int>, std::vector<SideTarget>> targets;
    for (const UnevenSide& s : uneven) {
      points.push_back(edge_points(parts, s));
      add_targets(before_corners, parts, s, points.back(), targets);
    }
    for (const auto& [side, wanted] : targets) fit_side(parts[side.first], side.second, wanted);
    out.uneven_gaps.clear();
    bool refining = false;
    for (std::size_t k = 0; k < uneven.size(); ++k) {
      const std::vector<double> gaps = pointwise_gaps(parts, uneven[k], points[k]);
      out.uneven_gaps.push_back(*std::max_element(gaps.begin(), gaps.end()));
      if (halvings < kMaxHalvings && out.uneven_gaps.back() > tolerance) {
        refining |= halve_spans(refined, uneven[k], points[k], gaps, tolerance);
      }
    }
    if (!refining) break;
  }
  out.joined = sides.size() - out.left.size() +
               static_cast<std::size_t>(std::count_if(out.uneven_gaps.begin(), out.uneven_gaps.end(),
                                                      [&](double gap) { return gap <= tolerance; }));
  for (std::size_t f = 0; f < fields.size(); ++f) fields[f] = parts[f].surface();
  return out;
}

}  // namespace hotmesh::geometry::detail
