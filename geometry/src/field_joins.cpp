// hotmesh geometry (internal): deflection fields joined along shared edges (field_joins.hpp).
#include "field_joins.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

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
  /// The poles along a side, in the order of increasing parameter: row or column k.
  std::vector<Vec3*> side_poles(int side) {
    std::vector<Vec3*> out;
    const std::size_t nu = u_count(), nv = v_count();
    if (along_u(side)) {
      const std::size_t j = side == 0 ? 0 : nv - 1;
      for (std::size_t i = 0; i < nu; ++i) out.push_back(&poles[i * nv + j]);
    } else {
      const std::size_t i = side == 2 ? 0 : nu - 1;
      for (std::size_t j = 0; j < nv; ++j) out.push_back(&poles[i * nv + j]);
    }
    return out;
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

/// Inserts into `to` (along `u_to`) the knots `from` has along its side, mapped affinely
/// from one parameter range to the other (reversed: end to start); a knot within rounding of
/// one `to` has already counts as it. Returns whether it inserted any.
bool take_knots(const FieldParts& from, bool u_from, FieldParts& to, bool u_to, bool reversed) {
  const std::vector<double>& kf = from.knots(u_from);
  const auto pf = static_cast<std::size_t>(from.degree(u_from));
  const double f0 = kf[pf], f1 = kf[kf.size() - pf - 1];
  bool inserted = false;
  for (const auto& [value, count] : interior_knots(kf, from.degree(u_from))) {
    const std::vector<double>& kt = to.knots(u_to);
    const auto pt = static_cast<std::size_t>(to.degree(u_to));
    const double t0 = kt[pt], t1 = kt[kt.size() - pt - 1];
    double fraction = (value - f0) / (f1 - f0);
    if (reversed) fraction = 1.0 - fraction;
    double x = t0 + fraction * (t1 - t0);
    const double snap = 1e-10 * (t1 - t0);
    int have = 0;
    for (const auto& [there, m] : interior_knots(kt, to.degree(u_to))) {
      if (std::abs(there - x) <= snap) {
        x = there;
        have = m;
      }
    }
    for (int m = have; m < count; ++m) {
      to.insert(u_to, x);
      inserted = true;
    }
  }
  return inserted;
}

}  // namespace

std::vector<SharedSide> join_fields(std::vector<BSplineSurface>& fields, std::span<const SharedSide> sides,
                                    std::span<const std::vector<FaceCorner>> corners) {
  std::vector<FieldParts> parts;
  parts.reserve(fields.size());
  for (const BSplineSurface& f : fields) parts.emplace_back(f);
  std::vector<SharedSide> joined, left;
  for (const SharedSide& s : sides) {
    const bool ua = along_u(s.a.side), ub = along_u(s.b.side);
    (parts[s.a.face].degree(ua) == parts[s.b.face].degree(ub) ? joined : left).push_back(s);
  }
  // 1. The same knots along every joined edge: a field's knots along one direction serve all
  // its sides that way, so insertions travel from face to face until none is needed.
  constexpr int kMaxPasses = 32;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    bool inserted = false;
    for (const SharedSide& s : joined) {
      const bool ua = along_u(s.a.side), ub = along_u(s.b.side);
      inserted |= take_knots(parts[s.a.face], ua, parts[s.b.face], ub, s.reversed);
      inserted |= take_knots(parts[s.b.face], ub, parts[s.a.face], ua, s.reversed);
    }
    if (!inserted) break;
  }
  // 2. The mean of the two rows of poles along each edge (corners apart), then the mean of
  // every field's corner pole at each corner point.
  for (const SharedSide& s : joined) {
    auto row_a = parts[s.a.face].side_poles(s.a.side);
    auto row_b = parts[s.b.face].side_poles(s.b.side);
    if (row_a.size() != row_b.size()) {  // the insertions did not settle (knots not within rounding)
      left.push_back(s);
      continue;
    }
    if (s.reversed) std::reverse(row_b.begin(), row_b.end());
    for (std::size_t i = 1; i + 1 < row_a.size(); ++i) {
      const Vec3 mean = 0.5 * (*row_a[i] + *row_b[i]);
      *row_a[i] = mean;
      *row_b[i] = mean;
    }
  }
  for (const std::vector<FaceCorner>& group : corners) {
    if (group.empty()) continue;
    Vec3 sum{};
    for (const FaceCorner& c : group) sum = sum + parts[c.face].corner(c.corner);
    const Vec3 mean = (1.0 / static_cast<double>(group.size())) * sum;
    for (const FaceCorner& c : group) parts[c.face].corner(c.corner) = mean;
  }
  for (std::size_t f = 0; f < fields.size(); ++f) fields[f] = parts[f].surface();
  return left;
}

}  // namespace hotmesh::geometry::detail
