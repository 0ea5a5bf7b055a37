// hotmesh geometry (internal): ordering, orienting and concatenating meridional curve pieces
// into one B-spline profile.
#include "cad/profile_chain.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <tuple>

#include "hotmesh/geometry/curve_projector.hpp"
#include "hotmesh/core/input_error.hpp"
#include "cad/occt_convert.hpp"

namespace hotmesh::geometry::detail {

namespace {

Vec2 start_of(const BSplineCurve2d& c) { return c.point(c.first_parameter()); }
Vec2 end_of(const BSplineCurve2d& c) { return c.point(c.last_parameter()); }

double length_of(const BSplineCurve2d& c) {
  constexpr int kSamples = 256;
  double length = 0.0;
  Vec2 previous = start_of(c);
  for (int i = 1; i <= kSamples; ++i) {
    const Vec2 next = c.point(c.first_parameter() + (c.last_parameter() - c.first_parameter()) * i / kSamples);
    length += distance(previous, next);
    previous = next;
  }
  return length;
}

/// Every point of `a` lies within the tolerance of `b`: `a` repeats (part of) `b`, as the
/// meridians of the two halves of a revolved face, or of faces cut apart by a slot, do.
bool covered_by(const BSplineCurve2d& a, const CurveProjector& b, double tolerance) {
  constexpr int kSamples = 16;
  for (int i = 0; i <= kSamples; ++i) {
    const double t = a.first_parameter() + (a.last_parameter() - a.first_parameter()) * i / kSamples;
    if (b.project(a.point(t), 0.0).distance > tolerance) return false;
  }
  return true;
}

/// "faces 3, 4" (or edges), sorted, each once.
std::string id_list(const std::vector<ProfilePiece>& pieces, const PieceWords& words) {
  std::vector<int> ids;
  for (const auto& piece : pieces) ids.push_back(piece.id);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::string text = std::string(words.piece) + (ids.size() == 1 ? " " : "s ");
  for (std::size_t i = 0; i < ids.size(); ++i) text += (i ? ", " : "") + std::to_string(ids[i]);
  return text;
}

BSplineCurve2d with_degree(const BSplineCurve2d& curve, int degree) {
  if (curve.degree() == degree) return curve;
  const Handle(Geom2d_BSplineCurve) occt = to_occt(curve);
  occt->IncreaseDegree(degree);
  return to_curve(occt);
}

}  // namespace

bool runs_backwards(const Vec2& start, const Vec2& end, double tolerance) {
  if (std::abs(end.y - start.y) > tolerance) return end.y < start.y;
  return end.x < start.x;
}

namespace {

/// The pieces less those that repeat (part of) another one, longest first.
std::vector<ProfilePiece> distinct_pieces(std::vector<ProfilePiece> pieces, double tolerance,
                                          const std::string& source, const PieceWords& words) {
  if (pieces.empty()) throw InputError::in(source, std::string("the ") + words.piece + "s have no " + words.curve);
  std::stable_sort(pieces.begin(), pieces.end(), [](const ProfilePiece& a, const ProfilePiece& b) {
    return length_of(a.curve) > length_of(b.curve);
  });
  std::vector<ProfilePiece> distinct;
  std::vector<CurveProjector> kept;
  for (auto& piece : pieces) {
    const bool repeated = std::any_of(kept.begin(), kept.end(), [&](const CurveProjector& other) {
      return covered_by(piece.curve, other, tolerance);
    });
    if (repeated) continue;
    kept.emplace_back(DeflectedCurve(piece.curve));
    distinct.push_back(std::move(piece));
  }
  return distinct;
}

bool ends_meet(const BSplineCurve2d& a, const BSplineCurve2d& b, double tolerance) {
  for (const Vec2& p : {start_of(a), end_of(a)}) {
    if (distance(p, start_of(b)) <= tolerance || distance(p, end_of(b)) <= tolerance) return true;
  }
  return false;
}

/// 2. The pieces chained end to end, starting from an end that no other piece touches (any,
/// if closed) and growing at whichever end of the chain the nearest remaining piece meets; each
/// piece reversed where it runs the other way. A gap is reported as the smallest there is.
std::vector<ProfilePiece> chain_pieces(const std::vector<ProfilePiece>& distinct, double tolerance,
                                       const std::string& source, const PieceWords& words) {
  const auto touches = [&](const Vec2& p, std::size_t self) {
    for (std::size_t k = 0; k < distinct.size(); ++k) {
      if (k == self) continue;
      if (distance(p, start_of(distinct[k].curve)) <= tolerance || distance(p, end_of(distinct[k].curve)) <= tolerance) {
        return true;
      }
    }
    return false;
  };
  std::vector<char> used(distinct.size(), 0);
  std::deque<ProfilePiece> chain;
  for (std::size_t k = 0; k < distinct.size() && chain.empty(); ++k) {
    if (!touches(start_of(distinct[k].curve), k)) {
      chain.push_back(distinct[k]);
    } else if (!touches(end_of(distinct[k].curve), k)) {
      chain.push_back({distinct[k].curve.reversed(), distinct[k].id});
    }
    if (!chain.empty()) used[k] = 1;
  }
  if (chain.empty()) {
    chain.push_back(distinct[0]);
    used[0] = 1;
  }
  for (;;) {
    const Vec2 back = end_of(chain.back().curve), front = start_of(chain.front().curve);
    std::size_t best = distinct.size();
    bool at_back = true, reverse = false;
    double best_gap = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < distinct.size(); ++k) {
      if (used[k]) continue;
      const Vec2 start = start_of(distinct[k].curve), end = end_of(distinct[k].curve);
      // (gap, joins at the back, reversed): after the back it must start there, before the front end there.
      for (const auto& [gap, back_end, reversed] : {std::tuple{distance(back, start), true, false},
                                                   std::tuple{distance(back, end), true, true},
                                                   std::tuple{distance(front, end), false, false},
                                                   std::tuple{distance(front, start), false, true}}) {
        if (gap < best_gap) {
          best_gap = gap;
          best = k;
          at_back = back_end;
          reverse = reversed;
        }
      }
    }
    if (best == distinct.size()) break;
    if (best_gap > tolerance) {
      throw InputError::in(source, std::string("the ") + words.curve + "s of " + id_list(distinct, words) +
                                       " do not form " + words.whole + ": " + words.piece + " " +
                                       std::to_string(distinct[best].id) + " is " + std::to_string(best_gap) +
                                       " away from the end of the others (tolerance " + std::to_string(tolerance) +
                                       ")");
    }
    used[best] = 1;
    ProfilePiece piece{reverse ? distinct[best].curve.reversed() : distinct[best].curve, distinct[best].id};
    if (at_back) {
      chain.push_back(std::move(piece));
    } else {
      chain.push_front(std::move(piece));
    }
  }
  return {chain.begin(), chain.end()};
}

/// 3. The chain oriented (runs_backwards), and the parameters of its joints, proportional to
/// length on [0, 1].
std::vector<double> orient_and_measure(std::vector<ProfilePiece>& chain, double tolerance, const std::string& source,
                                       const PieceWords& words) {
  if (runs_backwards(start_of(chain.front().curve), end_of(chain.back().curve), tolerance)) {
    std::reverse(chain.begin(), chain.end());
    for (auto& piece : chain) piece.curve = piece.curve.reversed();
  }
  std::vector<double> breaks{0.0};
  double total = 0.0;
  for (const auto& piece : chain) {
    total += length_of(piece.curve);
    breaks.push_back(total);
  }
  if (!(total > 0.0)) {
    throw InputError::in(source, std::string("the ") + words.curve + " of " + id_list(chain, words) + " has no length");
  }
  for (double& b : breaks) b /= total;
  breaks.back() = 1.0;
  return breaks;
}

/// 4. Concatenation at a common degree: shared end poles averaged, weights of each piece
/// scaled (which leaves a rational curve unchanged) to match at the joints, knot multiplicity
/// = degree there.
Profile concatenate(const std::vector<ProfilePiece>& chain, const std::vector<double>& breaks,
                    const std::string& source, const PieceWords& words) {
  int degree = 1;
  bool rational = false;
  for (const auto& piece : chain) {
    degree = std::max(degree, piece.curve.degree());
    rational = rational || piece.curve.is_rational();
  }
  const auto p = static_cast<std::size_t>(degree);
  std::vector<double> knots;
  std::vector<Vec2> poles;
  std::vector<double> weights;
  Profile profile{chain.front().curve, {}, {}};
  for (std::size_t k = 0; k < chain.size(); ++k) {
    if (breaks[k + 1] <= breaks[k]) {
      throw InputError::in(source, std::string(words.piece) + " " + std::to_string(chain[k].id) + " has a " +
                                       words.curve + " of no length");
    }
    const BSplineCurve2d c = with_degree(chain[k].curve, degree).reparametrized(breaks[k], breaks[k + 1]);
    std::vector<double> w = c.is_rational() ? c.weights() : std::vector<double>(c.poles().size(), 1.0);
    if (k > 0) {
      const double scale = weights.back() / w.front();
      for (double& x : w) x *= scale;
    }
    const std::size_t first = k == 0 ? 0 : 1;
    if (k > 0) {
      poles.back() = 0.5 * (poles.back() + c.poles().front());
      knots.pop_back();  // multiplicity degree + 1 -> degree at the joint
    }
    knots.insert(knots.end(), c.knots().begin() + static_cast<std::ptrdiff_t>(k == 0 ? 0 : p + 1), c.knots().end());
    poles.insert(poles.end(), c.poles().begin() + static_cast<std::ptrdiff_t>(first), c.poles().end());
    weights.insert(weights.end(), w.begin() + static_cast<std::ptrdiff_t>(first), w.end());
    if (profile.faces.empty() || profile.faces.back() != chain[k].id) {
      profile.faces.push_back(chain[k].id);
      profile.face_breaks.push_back(breaks[k]);
    }
  }
  profile.face_breaks.push_back(1.0);
  if (!rational) weights.clear();
  profile.curve = BSplineCurve2d(degree, std::move(knots), std::move(poles), std::move(weights));
  return profile;
}

/// Distinct pieces ordered end to end into one profile (steps 2 to 4 of join_profile).
Profile chain_profile(const std::vector<ProfilePiece>& distinct, double tolerance, const std::string& source,
                      const PieceWords& words) {
  std::vector<ProfilePiece> chain = chain_pieces(distinct, tolerance, source, words);
  const std::vector<double> breaks = orient_and_measure(chain, tolerance, source, words);
  return concatenate(chain, breaks, source, words);
}

}  // namespace

Profile join_profile(std::vector<ProfilePiece> pieces, double tolerance, const std::string& source,
                     const PieceWords& words) {
  return chain_profile(distinct_pieces(std::move(pieces), tolerance, source, words), tolerance, source, words);
}

std::vector<Profile> join_profiles(std::vector<ProfilePiece> pieces, double tolerance, const std::string& source) {
  std::vector<int> face_order;  // faces in the order given
  for (const auto& piece : pieces) {
    if (std::find(face_order.begin(), face_order.end(), piece.id) == face_order.end()) face_order.push_back(piece.id);
  }
  const std::vector<ProfilePiece> distinct = distinct_pieces(std::move(pieces), tolerance, source, kFaceWords);
  // Connected groups: pieces whose ends meet, directly or through others (union-find).
  std::vector<std::size_t> group(distinct.size());
  for (std::size_t k = 0; k < group.size(); ++k) group[k] = k;
  const auto root = [&](std::size_t k) {
    while (group[k] != k) k = group[k] = group[group[k]];
    return k;
  };
  for (std::size_t i = 0; i < distinct.size(); ++i) {
    for (std::size_t j = i + 1; j < distinct.size(); ++j) {
      if (ends_meet(distinct[i].curve, distinct[j].curve, tolerance)) group[root(j)] = root(i);
    }
  }
  std::vector<std::vector<ProfilePiece>> groups;
  std::vector<std::size_t> group_root;
  for (std::size_t k = 0; k < distinct.size(); ++k) {
    const std::size_t r = root(k);
    const auto it = std::find(group_root.begin(), group_root.end(), r);
    if (it == group_root.end()) {
      group_root.push_back(r);
      groups.push_back({distinct[k]});
    } else {
      groups[static_cast<std::size_t>(it - group_root.begin())].push_back(distinct[k]);
    }
  }
  const auto first_face = [&](const std::vector<ProfilePiece>& g) {
    std::size_t first = face_order.size();
    for (const auto& piece : g) {
      first = std::min(first, static_cast<std::size_t>(std::find(face_order.begin(), face_order.end(), piece.id) -
                                                       face_order.begin()));
    }
    return first;
  };
  std::stable_sort(groups.begin(), groups.end(),
                   [&](const auto& a, const auto& b) { return first_face(a) < first_face(b); });
  std::vector<Profile> profiles;
  for (const auto& g : groups) profiles.push_back(chain_profile(g, tolerance, source, kFaceWords));
  return profiles;
}

}  // namespace hotmesh::geometry::detail
