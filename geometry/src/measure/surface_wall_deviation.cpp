// hotmesh geometry: the two-sided distance between a discrete wall and a wall on CAD faces (see
// the second part of wall_deviation.hpp): the wall's faces sampled and projected onto the stage
// of the faces; the faces sampled over the part the wall covers, each sample's nearest wall face
// found in a box tree and samples beyond the wall's rim left out (the pieces and the tree are
// wall_pieces.hpp); the local maxima of both refined by a pattern search, the two directions
// driven as two_sided_distance.hpp does for curves too.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "hotmesh/geometry/surface_shape.hpp"
#include "hotmesh/geometry/wall_deviation.hpp"
#include "measure/two_sided_distance.hpp"
#include "measure/wall_pieces.hpp"

namespace hotmesh::geometry {

namespace {

using detail::clamp_to;
using detail::kRoundOff;
using detail::on_rim;
using detail::Piece;
using detail::piece_point;
using detail::PieceTree;
using detail::Refinement;
using detail::RunningMaximum;
using detail::WallBox;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// The pattern search starts at half the sample spacing and stops below this fraction of it.
constexpr double kSearchEnd = 1e-4;
constexpr int kMaxSearchEvaluations = 400;
/// At most this many samples per direction, and in all, of one CAD face.
constexpr double kMaxLineSamples = 16384.0;
constexpr double kMaxFaceSamples = 16777216.0;

/// The local maximum of f near (a, b), where f has `value`, by pattern search: the 8 points
/// (a + i h step_a, b + j h step_b), i, j in {-1, 0, 1}, put into the domain by `clamp`; move to
/// the best if it is higher, else halve h; h from 1/2 down to kSearchEnd. Returns the maximum
/// found and moves (a, b) there.
template <class F, class Clamp>
double climb(F&& f, Clamp&& clamp, double& a, double& b, double value, double step_a, double step_b) {
  constexpr std::array<std::array<int, 2>, 8> kDirections{
      {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {1, -1}, {-1, 1}, {-1, -1}}};
  double h = 0.5;
  int evaluations = 0;
  while (h >= kSearchEnd && evaluations < kMaxSearchEvaluations) {
    double best = value, best_a = a, best_b = b;
    for (const auto& [i, j] : kDirections) {
      const auto [ca, cb] = clamp(a + i * h * step_a, b + j * h * step_b);
      const double fc = f(ca, cb);
      ++evaluations;
      if (fc > best) {
        best = fc;
        best_a = ca;
        best_b = cb;
      }
    }
    if (best > value) {
      value = best;
      a = best_a;
      b = best_b;
    } else {
      h *= 0.5;
    }
  }
  return value;
}

/// A sample that may hide a higher maximum between it and its neighbours.
struct Candidate {
  /// Its value plus half the largest difference to a neighbour: how much higher a tent (a kink)
  /// between the samples can rise at most, twice what a parabola can.
  double bound;
  double value;
  std::size_t index;  ///< the piece, or the CAD face
  double a, b;        ///< its parameters
  double step_a, step_b;  ///< the sample spacing in them
  ShapeParameter hint;    ///< where its projection landed (wall side)
};

/// The largest |value - grid[neighbour]| over the 8 neighbours (i + di, j + dj) of a grid of
/// columns x rows that `valid` accepts.
template <class Valid>
double spread(const std::vector<double>& grid, std::size_t columns, std::size_t rows, std::size_t i, std::size_t j,
              Valid&& valid) {
  const double value = grid[i * rows + j];
  double largest = 0.0;
  for (int di = -1; di <= 1; ++di) {
    for (int dj = -1; dj <= 1; ++dj) {
      if ((di == 0 && dj == 0) || (di < 0 && i == 0) || (dj < 0 && j == 0)) continue;
      const std::size_t ni = i + static_cast<std::size_t>(di), nj = j + static_cast<std::size_t>(dj);
      if (ni >= columns || nj >= rows || !valid(ni, nj)) continue;
      largest = std::max(largest, std::abs(value - grid[ni * rows + nj]));
    }
  }
  return largest;
}

class PiecesToFaces;
class FacesToPieces;

/// Everything one measurement needs: the stage's faces, the wall's pieces, the part of each
/// CAD face the wall covers, the wall's size and median edge; its two directions are
/// PiecesToFaces and FacesToPieces.
class SurfaceMeasure {
 public:
  SurfaceMeasure(const SurfaceShape& shape, std::span<const Vec3> points, const WallFaces& faces,
                 const SurfaceWallOptions& options)
      : shape_(shape), options_(options), pieces_(detail::wall_pieces(points, faces)) {
    // The wall's size and its polygon edges' median length.
    std::vector<double> lengths;
    WallBox all;
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const auto corners = faces.corners(f);
      for (std::size_t k = 0; k < corners.size(); ++k) {
        const std::int32_t a = corners[k], b = corners[(k + 1) % corners.size()];
        lengths.push_back(distance(points[static_cast<std::size_t>(a)], points[static_cast<std::size_t>(b)]));
        all.add(points[static_cast<std::size_t>(a)]);
      }
    }
    round_off_ = kRoundOff * (pieces_.empty() ? 1.0 : distance(all.lo, all.hi));
    lengths.erase(std::remove_if(lengths.begin(), lengths.end(), [&](double l) { return !(l > round_off_); }),
                  lengths.end());
    median_edge_ = detail::median_length(lengths);
    for (std::size_t f = 0; f < shape.face_count(); ++f) {
      covered_.push_back({kInfinity, -kInfinity, kInfinity, -kInfinity});
    }
  }

  bool empty() const { return pieces_.empty(); }

  /// mesh_to_shape, and the part of each CAD face the wall's samples project onto.
  PiecesToFaces wall_side(WallDeviation& result);
  /// shape_to_mesh over the part of each CAD face that the wall's side found covered.
  FacesToPieces shape_side(WallDeviation& result) const;

  const SurfaceShape& shape() const { return shape_; }
  const SurfaceWallOptions& options() const { return options_; }
  const std::vector<Piece>& pieces() const { return pieces_; }
  const std::vector<ParameterRectangle>& covered() const { return covered_; }
  double round_off() const { return round_off_; }
  double median_edge() const { return median_edge_; }

  /// The part of its CAD face a projection lands on (beyond a free edge: on the edge).
  void cover(const ShapeParameter& p) {
    if (p.face < 0 || static_cast<std::size_t>(p.face) >= covered_.size() || !(p.t == p.t) || !(p.s == p.s)) return;
    const ParameterRectangle domain = shape_.face(static_cast<std::size_t>(p.face)).surface.domain();
    const double t = std::clamp(p.t, domain.u_first, domain.u_last);
    const double s = std::clamp(p.s, domain.v_first, domain.v_last);
    ParameterRectangle& r = covered_[static_cast<std::size_t>(p.face)];
    r = {std::min(r.u_first, t), std::max(r.u_last, t), std::min(r.v_first, s), std::max(r.v_last, s)};
  }

  void set_wall_point(WallDeviationPoint& w, std::size_t piece, double a, double b, const ShapePoint& q) const {
    w.distance = q.distance;
    w.point = piece_point(pieces_[piece], a, b);
    w.nearest = q.point;
    w.parameter = q.parameter.t;
    w.parameter_s = q.parameter.s;
    w.shape_face = q.parameter.face;
    w.edge = {-1, -1};
    w.face = pieces_[piece].face;
  }

  void set_shape_point(WallDeviationPoint& w, std::size_t face, double t, double s, const Vec3& x,
                       const PieceTree::Nearest& n) const {
    w.distance = n.distance;
    w.point = x;
    w.nearest = piece_point(pieces_[n.piece], n.a, n.b);
    w.parameter = t;
    w.parameter_s = s;
    w.shape_face = static_cast<int>(face);
    w.edge = {-1, -1};
    w.face = pieces_[n.piece].face;
  }

 private:
  const SurfaceShape& shape_;
  const SurfaceWallOptions& options_;
  std::vector<Piece> pieces_;
  std::vector<ParameterRectangle> covered_;  ///< per CAD face; empty (first > last): not covered
  double round_off_ = 0.0;
  double median_edge_ = 0.0;
};

/// Candidates are refined from the highest bound down while a bound beats the best found.
bool higher_bound(const Candidate& a, const Candidate& b) { return a.bound > b.bound; }
Refinement judge_bound(const Candidate& c, double best, double round_off) {
  return c.bound > best + round_off ? Refinement::refine : Refinement::stop;  // nor any after it
}

/// mesh_to_shape: each piece on a grid of face_samples intervals per direction, each point
/// projected onto the stage (a warm start from the previous one); the best sample of each piece
/// a candidate.
class PiecesToFaces {
 public:
  PiecesToFaces(SurfaceMeasure& measure, WallDeviation& result) : measure_(measure), result_(result) {}

  std::vector<Candidate> sample(RunningMaximum& maximum) {
    const SurfaceShape& shape = measure_.shape();
    const std::vector<Piece>& pieces = measure_.pieces();
    const int n = measure_.options().face_samples;
    const auto side = static_cast<std::size_t>(n) + 1;
    const double h = 1.0 / n;
    const double lambda = measure_.options().lambda;
    ShapeParameter hint = kNoHint;
    std::vector<double> grid(side * side);
    std::vector<ShapeParameter> where(side * side);
    std::vector<Candidate> candidates;
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      const Piece& g = pieces[k];
      const auto valid = [&](std::size_t i, std::size_t j) { return g.corners == 4 || i + j <= side - 1; };
      std::size_t top = 0;  // the piece's highest sample
      double top_value = -kInfinity;
      for (std::size_t i = 0; i < side; ++i) {
        for (std::size_t j = 0; j < side && valid(i, j); ++j) {
          const double a = static_cast<double>(i) * h, b = static_cast<double>(j) * h;
          const ShapePoint q = shape.project(piece_point(g, a, b), lambda, hint);
          hint = q.parameter;
          grid[i * side + j] = q.distance;
          where[i * side + j] = q.parameter;
          if (std::isnan(q.distance)) maximum.not_finite = true;
          measure_.cover(q.parameter);
          if (q.distance > top_value) {
            top_value = q.distance;
            top = i * side + j;
          }
          if (maximum.raise(q.distance)) measure_.set_wall_point(result_.mesh_to_shape, k, a, b, q);
        }
      }
      const std::size_t ti = top / side, tj = top % side;
      const double value = grid[top];
      const double bound = value + 0.5 * spread(grid, side, side, ti, tj, valid);
      if (bound > maximum.best + measure_.round_off()) {
        candidates.push_back({bound, value, k, static_cast<double>(ti) * h, static_cast<double>(tj) * h, h, h, where[top]});
      }
    }
    return candidates;
  }

  static bool higher(const Candidate& a, const Candidate& b) { return higher_bound(a, b); }
  Refinement judge(const Candidate& c, double best) const { return judge_bound(c, best, measure_.round_off()); }

  void refine(const Candidate& c, RunningMaximum& maximum) {
    const SurfaceShape& shape = measure_.shape();
    const double lambda = measure_.options().lambda;
    const Piece& g = measure_.pieces()[c.index];
    ShapeParameter near = c.hint;
    const auto f = [&](double a, double b) {
      const ShapePoint q = shape.project(piece_point(g, a, b), lambda, near);
      near = q.parameter;
      return q.distance;
    };
    double a = c.a, b = c.b;
    const double value = climb(f, [&](double u, double v) { return clamp_to(g, u, v); }, a, b, c.value, c.step_a, c.step_b);
    if (maximum.raise(value)) {
      measure_.set_wall_point(result_.mesh_to_shape, c.index, a, b, shape.project(piece_point(g, a, b), lambda, near));
    }
  }

 private:
  SurfaceMeasure& measure_;
  WallDeviation& result_;
};

/// shape_to_mesh: each CAD face over the part of its rectangle the wall covers, on a grid at
/// most shape_spacing median edges apart; each sample's nearest piece found in the box tree,
/// samples not on the face or beyond the wall's rim left out; each local maximum of a face's
/// grid a candidate.
class FacesToPieces {
 public:
  FacesToPieces(const SurfaceMeasure& measure, WallDeviation& result)
      : measure_(measure), result_(result), tree_(measure.pieces()), lambda_(measure.options().lambda),
        spacing_(measure.median_edge() > 0.0 ? measure.options().shape_spacing * measure.median_edge() : kInfinity) {}

  std::vector<Candidate> sample(RunningMaximum& maximum) {
    std::vector<Candidate> candidates;
    for (std::size_t face = 0; face < measure_.covered().size(); ++face) {
      const ParameterRectangle r = measure_.covered()[face];
      if (!(r.u_first <= r.u_last) || !(r.v_first <= r.v_last)) continue;  // no sample of the wall on it
      const FaceGrid g = face_grid(face, r);
      sample_face(face, g, maximum);
      face_peaks(face, g, maximum.best, candidates);
    }
    return candidates;
  }

  static bool higher(const Candidate& a, const Candidate& b) { return higher_bound(a, b); }
  Refinement judge(const Candidate& c, double best) const { return judge_bound(c, best, measure_.round_off()); }

  void refine(const Candidate& c, RunningMaximum& maximum) {
    const SurfaceShape& shape = measure_.shape();
    const ParameterRectangle r = measure_.covered()[c.index];
    const auto clamp = [&](double t, double s) {
      return std::pair{std::clamp(t, r.u_first, r.u_last), std::clamp(s, r.v_first, r.v_last)};
    };
    const auto f = [&](double t, double s) {
      if (!shape.holds(c.index, t, s)) return -kInfinity;
      const PieceTree::Nearest w = tree_.nearest(at(c.index, t, s), near_);
      near_ = w.piece;
      return on_rim(measure_.pieces()[w.piece], w.a, w.b) ? -kInfinity : w.distance;
    };
    double t = c.a, s = c.b;
    const double value = climb(f, clamp, t, s, c.value, c.step_a, c.step_b);
    if (maximum.raise(value)) {
      const Vec3 x = at(c.index, t, s);
      measure_.set_shape_point(result_.shape_to_mesh, c.index, t, s, x, tree_.nearest(x, near_));
    }
  }

 private:
  /// A CAD face's samples over the covered part r of its rectangle: columns x rows points, dt
  /// and ds apart, the last of each line at r's end.
  struct FaceGrid {
    ParameterRectangle r;
    std::size_t columns;
    std::size_t rows;
    double dt;
    double ds;
    double t(std::size_t i) const { return parameter(r.u_first, r.u_last, dt, i, columns); }
    double s(std::size_t j) const { return parameter(r.v_first, r.v_last, ds, j, rows); }
  };

  static double parameter(double first, double last, double step, std::size_t k, std::size_t n) {
    return k + 1 == n ? last : first + static_cast<double>(k) * step;
  }

  Vec3 at(std::size_t face, double t, double s) const {
    return measure_.shape().at({t, s, static_cast<int>(face)}, lambda_, {}).point;
  }

  /// The face's longest line across r in one direction (5 lines, each 8 chords).
  double longest_line(std::size_t face, const ParameterRectangle& r, bool along_t) const {
    double longest = 0.0;
    for (int line = 0; line < 5; ++line) {
      double length = 0.0;
      const double other = along_t ? r.v_first + (r.v_last - r.v_first) * (line + 0.5) / 5.0
                                   : r.u_first + (r.u_last - r.u_first) * (line + 0.5) / 5.0;
      Vec3 previous;
      for (int k = 0; k <= 8; ++k) {
        const double p = along_t ? r.u_first + (r.u_last - r.u_first) * k / 8.0
                                 : r.v_first + (r.v_last - r.v_first) * k / 8.0;
        const Vec3 x = along_t ? at(face, p, other) : at(face, other, p);
        if (k > 0) length += distance(previous, x);
        previous = x;
      }
      longest = std::max(longest, length);
    }
    return longest;
  }

  double sample_count(double length, double range) const {
    if (!(range > 0.0)) return 0.0;
    const double c = std::ceil(length / spacing_);
    return std::isfinite(c) ? std::clamp(c, 1.0, kMaxLineSamples) : 1.0;
  }

  /// Samples per direction: the face's longest line across r in that direction over the spacing.
  FaceGrid face_grid(std::size_t face, const ParameterRectangle& r) const {
    double nt = sample_count(longest_line(face, r, true), r.u_last - r.u_first);
    double ns = sample_count(longest_line(face, r, false), r.v_last - r.v_first);
    if ((nt + 1.0) * (ns + 1.0) > kMaxFaceSamples) {
      const double scale = std::sqrt(kMaxFaceSamples / ((nt + 1.0) * (ns + 1.0)));
      nt = std::floor(nt * scale);
      ns = std::floor(ns * scale);
    }
    const auto columns = static_cast<std::size_t>(nt) + 1, rows = static_cast<std::size_t>(ns) + 1;
    const double dt = nt > 0.0 ? (r.u_last - r.u_first) / nt : 0.0;
    const double ds = ns > 0.0 ? (r.v_last - r.v_first) / ns : 0.0;
    return {r, columns, rows, dt, ds};
  }

  /// grid_: the distance of each sample of the face that is on it and under the wall,
  /// -infinity for the others.
  void sample_face(std::size_t face, const FaceGrid& g, RunningMaximum& maximum) {
    const SurfaceShape& shape = measure_.shape();
    grid_.assign(g.columns * g.rows, -kInfinity);
    for (std::size_t i = 0; i < g.columns; ++i) {
      for (std::size_t j = 0; j < g.rows; ++j) {
        const double t = g.t(i);
        const double s = g.s(j);
        ++result_.shape_samples;
        if (!shape.holds(face, t, s)) {  // not on the face: beyond its trimming loops
          ++result_.uncovered_samples;
          continue;
        }
        const Vec3 x = at(face, t, s);
        const PieceTree::Nearest w = tree_.nearest(x, near_);
        near_ = w.piece;
        if (on_rim(measure_.pieces()[w.piece], w.a, w.b)) {
          ++result_.uncovered_samples;
          continue;
        }
        grid_[i * g.rows + j] = w.distance;
        if (std::isnan(w.distance) || !is_finite(x)) maximum.not_finite = true;
        if (maximum.raise(w.distance)) measure_.set_shape_point(result_.shape_to_mesh, face, t, s, x, w);
      }
    }
  }

  /// The local maxima of the face's samples whose bound beats `best`.
  void face_peaks(std::size_t face, const FaceGrid& g, double best, std::vector<Candidate>& candidates) const {
    const std::size_t columns = g.columns, rows = g.rows;
    const auto covered = [&](std::size_t i, std::size_t j) { return grid_[i * rows + j] > -kInfinity; };
    for (std::size_t i = 0; i < columns; ++i) {
      for (std::size_t j = 0; j < rows; ++j) {
        if (!covered(i, j)) continue;
        const double value = grid_[i * rows + j];
        // A local maximum: no covered neighbour higher.
        bool peak = true;
        for (int di = -1; di <= 1 && peak; ++di) {
          for (int dj = -1; dj <= 1 && peak; ++dj) {
            if ((di < 0 && i == 0) || (dj < 0 && j == 0)) continue;
            const std::size_t ni = i + static_cast<std::size_t>(di), nj = j + static_cast<std::size_t>(dj);
            if (ni < columns && nj < rows && covered(ni, nj) && grid_[ni * rows + nj] > value) peak = false;
          }
        }
        if (!peak) continue;
        const double bound = value + 0.5 * spread(grid_, columns, rows, i, j, covered);
        if (bound > best + measure_.round_off()) {
          candidates.push_back({bound, value, face, g.t(i), g.s(j), g.dt, g.ds, kNoHint});
        }
      }
    }
  }

  const SurfaceMeasure& measure_;
  WallDeviation& result_;
  const PieceTree tree_;
  double lambda_;
  double spacing_;
  std::uint32_t near_ = 0;    ///< the piece nearest the last sample: the next query's first bound
  std::vector<double> grid_;  ///< one CAD face's samples at a time
};

PiecesToFaces SurfaceMeasure::wall_side(WallDeviation& result) { return {*this, result}; }
FacesToPieces SurfaceMeasure::shape_side(WallDeviation& result) const { return {*this, result}; }

}  // namespace

WallDeviation wall_deviation(const SurfaceShape& shape, std::span<const Vec3> points, const WallFaces& faces,
                             const SurfaceWallOptions& options) {
  if (options.face_samples < 1 || options.face_samples > 1000) {
    throw std::invalid_argument("wall_deviation: face_samples must be 1 to 1000");
  }
  if (!(options.shape_spacing > 0.0) || !std::isfinite(options.shape_spacing) || !std::isfinite(options.lambda)) {
    throw std::invalid_argument("wall_deviation: shape_spacing must be positive and lambda finite");
  }
  WallDeviation result;
  SurfaceMeasure measure(shape, points, faces, options);
  result.faces = faces.size();
  if (measure.empty()) return result;
  detail::measure_both_directions(measure, result);
  return result;
}

}  // namespace hotmesh::geometry
