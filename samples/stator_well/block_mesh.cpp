// hotmesh sample stator_well: the multi-block quad mesher (see block_mesh.hpp).
#include "block_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

namespace hotmesh::samples {

namespace {

constexpr int kArcSamplesPerSpan = 128;  // chord sums over these give arc lengths to ~1e-6
constexpr int kFieldSamples = 4000;      // integration of the spacing field along a class

std::string where(const Vec2& p) { return "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ")"; }

/// Union-find with parity: parity(x) says whether x's direction is reversed relative to its root.
class ParityUnion {
 public:
  explicit ParityUnion(std::size_t n) : parent_(n), parity_(n, 0) { std::iota(parent_.begin(), parent_.end(), 0); }
  std::pair<std::size_t, int> find(std::size_t x) {
    int p = 0;
    std::size_t r = x;
    while (parent_[r] != r) {
      p ^= parity_[r];
      r = parent_[r];
    }
    // Path compression keeping parities.
    std::size_t y = x;
    int py = p;
    while (parent_[y] != y) {
      const std::size_t next = parent_[y];
      const int pn = py ^ parity_[y];
      parent_[y] = r;
      parity_[y] = py;
      y = next;
      py = pn;
    }
    return {r, p};
  }
  /// a and b run the same way if `parity` is 0. False if that contradicts what is known.
  bool unite(std::size_t a, std::size_t b, int parity) {
    const auto [ra, pa] = find(a);
    const auto [rb, pb] = find(b);
    if (ra == rb) return (pa ^ pb) == parity;
    parent_[rb] = ra;
    parity_[rb] = pa ^ pb ^ parity;
    return true;
  }

 private:
  std::vector<std::size_t> parent_;
  std::vector<int> parity_;
};

/// Closest point of a curve to p: (parameter, distance), by sampling then Newton.
std::pair<double, double> closest(const BSplineCurve2d& c, const std::vector<std::array<double, 2>>& samples, Vec2 p) {
  double best_t = samples.front()[0];
  double best = distance(c.point(best_t), p);
  for (const auto& s : samples) {
    const double d = distance(c.point(s[0]), p);
    if (d < best) {
      best = d;
      best_t = s[0];
    }
  }
  double t = best_t;
  for (int it = 0; it < 30; ++it) {
    const auto d = c.derivatives(t);
    const Vec2 e = d.point - p;
    const double g = dot(e, d.first);
    const double h = dot(d.first, d.first) + dot(e, d.second);
    if (h <= 0.0) break;
    const double next = std::clamp(t - g / h, c.first_parameter(), c.last_parameter());
    if (std::abs(next - t) < 1e-15) break;
    t = next;
  }
  return {t, distance(c.point(t), p)};
}

}  // namespace

BlockMesher::BlockMesher(BlockLayout layout, SpacingField field) : layout_(std::move(layout)), field_(field) {
  if (layout_.loop.empty() || layout_.blocks.empty()) throw std::invalid_argument("block layout: no loop or no blocks");
  if (!(field_.growth > 1.0 && field_.wall_spacing > 0.0 && field_.spacing >= field_.wall_spacing)) {
    throw std::invalid_argument("block layout: the spacing field needs growth > 1 and 0 < wall_spacing <= spacing");
  }
  // 1. The loop: arc-length tables, coordinates of curve starts, walls joined tangentially.
  const std::size_t nc = layout_.loop.size();
  curve_start_.assign(nc + 1, 0.0);
  arc_.resize(nc);
  for (std::size_t i = 0; i < nc; ++i) {
    const BSplineCurve2d& c = layout_.loop[i].curve;
    const auto breaks = c.breakpoints();
    auto& table = arc_[i];
    table.push_back({breaks.front(), 0.0});
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
      for (int j = 1; j <= kArcSamplesPerSpan; ++j) {
        const double t = j == kArcSamplesPerSpan ? breaks[k + 1]
                                                 : breaks[k] + (breaks[k + 1] - breaks[k]) * j / kArcSamplesPerSpan;
        table.push_back({t, table.back()[1] + distance(c.point(t), c.point(table.back()[0]))});
      }
    }
    curve_start_[i + 1] = curve_start_[i] + table.back()[1];
    const Vec2 next_start = layout_.loop[(i + 1) % nc].curve.point(layout_.loop[(i + 1) % nc].curve.first_parameter());
    if (distance(c.point(c.last_parameter()), next_start) > 1e-12 * (1.0 + norm(next_start))) {
      throw std::invalid_argument("block layout: loop curve " + std::to_string(i) + " does not end where the next starts");
    }
  }
  const double total = curve_start_.back();
  std::vector<int> chain(nc);
  {
    ParityUnion joined(nc);
    for (std::size_t i = 0; i < nc; ++i) {
      const std::size_t j = (i + 1) % nc;
      const auto& a = layout_.loop[i].curve;
      const auto& b = layout_.loop[j].curve;
      const Vec2 ta = a.derivatives(a.last_parameter()).first;
      const Vec2 tb = b.derivatives(b.first_parameter()).first;
      const double sine = (ta.x * tb.y - ta.y * tb.x) / (norm(ta) * norm(tb));
      if (layout_.loop[i].wall && layout_.loop[j].wall && std::abs(sine) < 1e-6 && dot(ta, tb) > 0.0) joined.unite(i, j, 0);
    }
    for (std::size_t i = 0; i < nc; ++i) chain[i] = layout_.loop[i].wall ? static_cast<int>(joined.find(i).first) : -1;
  }
  const double eps = 1e-12 * total;
  const auto curves_at = [&](double s) {  // the curves touching loop coordinate s
    std::vector<std::size_t> found;
    for (std::size_t i = 0; i < nc; ++i) {
      if (s >= curve_start_[i] - eps && s <= curve_start_[i + 1] + eps) found.push_back(i);
    }
    if (s <= eps || s >= total - eps) found.push_back(s <= eps ? nc - 1 : 0);
    return found;
  };
  const auto curve_after = [&](double s) {  // the curve that holds [s, s + ds)
    s = std::fmod(s, total);
    const auto it = std::upper_bound(curve_start_.begin(), curve_start_.end(), s + eps);
    return std::min(static_cast<std::size_t>(it - curve_start_.begin()) - 1, nc - 1);
  };
  const auto curve_before = [&](double s) {  // the curve that holds (s - ds, s]
    if (s <= eps) s += total;
    const auto it = std::lower_bound(curve_start_.begin(), curve_start_.end(), s - eps);
    return std::min(static_cast<std::size_t>(it - curve_start_.begin()) - 1, nc - 1);
  };

  // 2. Vertices on the loop.
  double size = 0.0;
  for (const auto& v : layout_.vertices) size = std::max(size, norm(v));
  const double on_loop = 1e-9 * std::max(size, total);
  vertex_s_.assign(layout_.vertices.size(), -1.0);
  for (std::size_t v = 0; v < layout_.vertices.size(); ++v) {
    for (std::size_t i = 0; i < nc && vertex_s_[v] < 0.0; ++i) {
      const auto [t, d] = closest(layout_.loop[i].curve, arc_[i], layout_.vertices[v]);
      if (d > on_loop) continue;
      const auto& table = arc_[i];
      const auto it = std::lower_bound(table.begin(), table.end(), t, [](const auto& e, double x) { return e[0] < x; });
      double s = table.back()[1];
      if (it == table.begin()) {
        s = 0.0;
      } else if (it != table.end()) {
        const auto& a = *(it - 1);
        const auto& b = *it;
        s = a[1] + (b[1] - a[1]) * (t - a[0]) / (b[0] - a[0]);
      }
      vertex_s_[v] = std::fmod(curve_start_[i] + s, total);
      if (vertex_s_[v] > total - eps) vertex_s_[v] = 0.0;
    }
  }

  // 3. Edges and block sides.
  std::map<std::pair<int, int>, int> edge_of;
  std::vector<int> uses;
  block_sides_.resize(layout_.blocks.size());
  for (std::size_t b = 0; b < layout_.blocks.size(); ++b) {
    const auto& q = layout_.blocks[b];
    double area = 0.0;
    for (int k = 0; k < 4; ++k) {
      const Vec2& p = layout_.vertices.at(static_cast<std::size_t>(q[static_cast<std::size_t>(k)]));
      const Vec2& n = layout_.vertices.at(static_cast<std::size_t>(q[static_cast<std::size_t>((k + 1) % 4)]));
      area += p.x * n.y - n.x * p.y;
    }
    if (!(area > 0.0)) throw std::invalid_argument("block " + std::to_string(b) + " is not counter-clockwise");
    const std::array<std::pair<int, int>, 4> sides{{{q[0], q[1]}, {q[1], q[2]}, {q[3], q[2]}, {q[0], q[3]}}};
    for (std::size_t k = 0; k < 4; ++k) {
      const auto [a, c] = sides[k];
      const auto key = std::minmax(a, c);
      auto [it, fresh] = edge_of.try_emplace(key, static_cast<int>(edges_.size()));
      if (fresh) {
        edges_.push_back({key.first, key.second});
        uses.push_back(0);
      }
      if (++uses[static_cast<std::size_t>(it->second)] > 2) {
        throw std::invalid_argument("block " + std::to_string(b) + ": side " + where(layout_.vertices[static_cast<std::size_t>(a)]) +
                                    " - " + where(layout_.vertices[static_cast<std::size_t>(c)]) + " is used by three blocks");
      }
      block_sides_[b][k] = {it->second, a < c};
    }
  }
  // A boundary side runs along the loop in its block's counter-clockwise order.
  for (std::size_t b = 0; b < layout_.blocks.size(); ++b) {
    const auto& q = layout_.blocks[b];
    for (int k = 0; k < 4; ++k) {
      const int a = q[static_cast<std::size_t>(k)], c = q[static_cast<std::size_t>((k + 1) % 4)];
      Edge& e = edges_[static_cast<std::size_t>(edge_of.at(std::minmax(a, c)))];
      if (uses[static_cast<std::size_t>(&e - edges_.data())] != 1) continue;
      const double sa = vertex_s_[static_cast<std::size_t>(a)], sc = vertex_s_[static_cast<std::size_t>(c)];
      if (sa < 0.0 || sc < 0.0) {
        throw std::invalid_argument("block " + std::to_string(b) + ": boundary side " + where(layout_.vertices[static_cast<std::size_t>(a)]) +
                                    " - " + where(layout_.vertices[static_cast<std::size_t>(c)]) + " has a corner off the loop");
      }
      const double end = sc > sa ? sc : sc + total;
      if (end - sa > 0.5 * total) {
        throw std::invalid_argument("block " + std::to_string(b) + ": boundary side " + where(layout_.vertices[static_cast<std::size_t>(a)]) +
                                    " - " + where(layout_.vertices[static_cast<std::size_t>(c)]) + " runs against the loop");
      }
      e.boundary = true;
      e.loop_forward = a == e.v0;
      e.s0 = e.loop_forward ? sa : end;
      e.s1 = e.loop_forward ? end : sa;
      e.length = end - sa;
    }
  }
  for (Edge& e : edges_) {
    if (!e.boundary) e.length = distance(layout_.vertices[static_cast<std::size_t>(e.v0)], layout_.vertices[static_cast<std::size_t>(e.v1)]);
  }

  // 4. Classes of opposite sides.
  ParityUnion classes(edges_.size());
  for (std::size_t b = 0; b < block_sides_.size(); ++b) {
    const auto& s = block_sides_[b];
    for (const auto& [i, j] : {std::pair{0, 2}, std::pair{3, 1}}) {
      const Side& x = s[static_cast<std::size_t>(i)];
      const Side& y = s[static_cast<std::size_t>(j)];
      if (!classes.unite(static_cast<std::size_t>(x.edge), static_cast<std::size_t>(y.edge), x.forward == y.forward ? 0 : 1)) {
        throw std::invalid_argument("block " + std::to_string(b) + ": node counts cannot match (inconsistent orientation)");
      }
    }
  }
  std::map<std::size_t, int> class_of_root;
  std::vector<std::array<bool, 2>> clustered;
  std::vector<int> members;
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    const auto [root, parity] = classes.find(i);
    auto [it, fresh] = class_of_root.try_emplace(root, static_cast<int>(classes_.size()));
    if (fresh) {
      classes_.emplace_back();
      clustered.push_back({false, false});
      members.push_back(0);
    }
    Edge& e = edges_[i];
    e.klass = it->second;
    e.flipped = parity != 0;
    auto& c = classes_[static_cast<std::size_t>(e.klass)];
    c.length += e.length;
    ++members[static_cast<std::size_t>(e.klass)];
    // Does the side meet a wall transversally at its ends?
    for (int end = 0; end < 2; ++end) {
      const int v = end == 0 ? e.v0 : e.v1;
      const double s = vertex_s_[static_cast<std::size_t>(v)];
      if (s < 0.0) continue;
      std::set<int> walls;
      for (std::size_t k : curves_at(s)) {
        if (chain[k] >= 0) walls.insert(chain[k]);
      }
      if (e.boundary) {  // the wall the side itself runs along, next to this end
        const bool leaving = (end == 0) == e.loop_forward;  // the loop leaves v along the side
        walls.erase(chain[leaving ? curve_after(s) : curve_before(s)]);
      }
      if (!walls.empty()) clustered[static_cast<std::size_t>(e.klass)][static_cast<std::size_t>(end ^ (e.flipped ? 1 : 0))] = true;
    }
  }
  for (std::size_t k = 0; k < classes_.size(); ++k) {
    Class& c = classes_[k];
    c.length /= members[k];
    // Cells of the spacing field from the reference start, at refinement 1.
    const auto h = [&](double x) {
      double d = INFINITY;
      if (clustered[k][0]) d = std::min(d, x);
      if (clustered[k][1]) d = std::min(d, c.length - x);
      return std::min(field_.spacing, field_.wall_spacing + (field_.growth - 1.0) * d);
    };
    c.u.resize(kFieldSamples + 1);
    c.cells.resize(kFieldSamples + 1);
    c.u[0] = 0.0;
    c.cells[0] = 0.0;
    for (int i = 1; i <= kFieldSamples; ++i) {
      const double a = c.length * (i - 1) / kFieldSamples, b = c.length * i / kFieldSamples;
      c.u[static_cast<std::size_t>(i)] = static_cast<double>(i) / kFieldSamples;
      c.cells[static_cast<std::size_t>(i)] =
          c.cells[static_cast<std::size_t>(i - 1)] + (b - a) * (1.0 / h(a) + 4.0 / h(0.5 * (a + b)) + 1.0 / h(b)) / 6.0;
    }
  }
}

std::vector<int> BlockMesher::class_cells(double refinement) const {
  std::vector<int> n;
  n.reserve(classes_.size());
  for (const Class& c : classes_) n.push_back(std::max(1, static_cast<int>(std::lround(refinement * c.cells.back()))));
  return n;
}

std::int64_t BlockMesher::quad_count(double refinement) const {
  const auto n = class_cells(refinement);
  std::int64_t quads = 0;
  for (const auto& s : block_sides_) {
    quads += std::int64_t{n[static_cast<std::size_t>(edges_[static_cast<std::size_t>(s[0].edge)].klass)]} *
             n[static_cast<std::size_t>(edges_[static_cast<std::size_t>(s[3].edge)].klass)];
  }
  return quads;
}

std::int64_t BlockMesher::node_count(double refinement) const {
  const auto n = class_cells(refinement);
  std::int64_t nodes = static_cast<std::int64_t>(layout_.vertices.size());
  for (const Edge& e : edges_) nodes += n[static_cast<std::size_t>(e.klass)] - 1;
  for (const auto& s : block_sides_) {
    nodes += std::int64_t{n[static_cast<std::size_t>(edges_[static_cast<std::size_t>(s[0].edge)].klass)] - 1} *
             (n[static_cast<std::size_t>(edges_[static_cast<std::size_t>(s[3].edge)].klass)] - 1);
  }
  return nodes;
}

std::vector<double> BlockMesher::fractions(const Class& c, int n) const {
  std::vector<double> u(static_cast<std::size_t>(n) + 1);
  const double total = c.cells.back();
  std::size_t j = 0;
  for (int i = 0; i <= n; ++i) {
    const double target = total * i / n;
    while (j + 1 < c.cells.size() && c.cells[j + 1] < target) ++j;
    if (i == 0 || i == n) {
      u[static_cast<std::size_t>(i)] = i == 0 ? 0.0 : 1.0;
      continue;
    }
    const double w = (target - c.cells[j]) / (c.cells[j + 1] - c.cells[j]);
    u[static_cast<std::size_t>(i)] = c.u[j] + w * (c.u[j + 1] - c.u[j]);
  }
  return u;
}

Vec2 BlockMesher::loop_point(double s) const {
  const double total = curve_start_.back();
  s = std::fmod(s, total);
  const auto it = std::upper_bound(curve_start_.begin(), curve_start_.end(), s);
  const std::size_t i = std::min(static_cast<std::size_t>(it - curve_start_.begin()) - 1, layout_.loop.size() - 1);
  const auto& table = arc_[i];
  const double local = s - curve_start_[i];
  const auto at = std::lower_bound(table.begin(), table.end(), local, [](const auto& e, double x) { return e[1] < x; });
  double t = table.back()[0];
  if (at == table.begin()) {
    t = table.front()[0];
  } else if (at != table.end()) {
    const auto& a = *(at - 1);
    const auto& b = *at;
    t = a[0] + (b[0] - a[0]) * (local - a[1]) / (b[1] - a[1]);
  }
  return layout_.loop[i].curve.point(t);
}

QuadMesh BlockMesher::mesh(double refinement) const {
  const auto n = class_cells(refinement);
  std::vector<std::vector<double>> u(classes_.size());
  for (std::size_t k = 0; k < classes_.size(); ++k) u[k] = fractions(classes_[k], n[k]);

  QuadMesh out;
  out.nodes = layout_.vertices;
  // Edge nodes, in each edge's canonical direction v0 -> v1.
  std::vector<std::int32_t> edge_first(edges_.size());
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    const Edge& e = edges_[i];
    const auto& f = u[static_cast<std::size_t>(e.klass)];
    const std::size_t cells = f.size() - 1;
    edge_first[i] = static_cast<std::int32_t>(out.nodes.size());
    for (std::size_t j = 1; j < cells; ++j) {
      const double t = e.flipped ? 1.0 - f[cells - j] : f[j];  // fraction from v0
      if (e.boundary) {
        out.nodes.push_back(loop_point(e.s0 + t * (e.s1 - e.s0)));
      } else {
        const Vec2& a = layout_.vertices[static_cast<std::size_t>(e.v0)];
        const Vec2& b = layout_.vertices[static_cast<std::size_t>(e.v1)];
        out.nodes.push_back(a + t * (b - a));
      }
    }
  }
  // The nodes of a block side from its first to its last corner.
  const auto side_nodes = [&](const Side& s) {
    const Edge& e = edges_[static_cast<std::size_t>(s.edge)];
    const std::size_t cells = u[static_cast<std::size_t>(e.klass)].size() - 1;
    std::vector<std::int32_t> ids{e.v0};
    for (std::size_t j = 1; j < cells; ++j) ids.push_back(edge_first[static_cast<std::size_t>(s.edge)] + static_cast<std::int32_t>(j - 1));
    ids.push_back(e.v1);
    if (!s.forward) std::reverse(ids.begin(), ids.end());
    return ids;
  };
  for (std::size_t b = 0; b < block_sides_.size(); ++b) {
    const auto& s = block_sides_[b];
    const auto bottom = side_nodes(s[0]), right = side_nodes(s[1]), top = side_nodes(s[2]), left = side_nodes(s[3]);
    const Edge& ei = edges_[static_cast<std::size_t>(s[0].edge)];
    const Edge& ej = edges_[static_cast<std::size_t>(s[3].edge)];
    // Fractions along the block's i and j directions (bottom and left sides).
    auto xi = u[static_cast<std::size_t>(ei.klass)];
    if (ei.flipped == s[0].forward) {
      std::reverse(xi.begin(), xi.end());
      for (double& x : xi) x = 1.0 - x;
    }
    auto eta = u[static_cast<std::size_t>(ej.klass)];
    if (ej.flipped == s[3].forward) {
      std::reverse(eta.begin(), eta.end());
      for (double& x : eta) x = 1.0 - x;
    }
    const std::size_t ni = bottom.size(), nj = left.size();
    std::vector<std::int32_t> grid(ni * nj);
    const auto at = [&](std::size_t i, std::size_t j) -> std::int32_t& { return grid[j * ni + i]; };
    for (std::size_t i = 0; i < ni; ++i) {
      at(i, 0) = bottom[i];
      at(i, nj - 1) = top[i];
    }
    for (std::size_t j = 0; j < nj; ++j) {
      at(0, j) = left[j];
      at(ni - 1, j) = right[j];
    }
    const auto p = [&](std::int32_t id) { return out.nodes[static_cast<std::size_t>(id)]; };
    const Vec2 c00 = p(bottom.front()), c10 = p(bottom.back()), c01 = p(top.front()), c11 = p(top.back());
    for (std::size_t j = 1; j + 1 < nj; ++j) {
      for (std::size_t i = 1; i + 1 < ni; ++i) {
        const double x = xi[i], y = eta[j];
        const Vec2 q = (1.0 - y) * p(bottom[i]) + y * p(top[i]) + (1.0 - x) * p(left[j]) + x * p(right[j]) -
                       ((1.0 - x) * (1.0 - y) * c00 + x * (1.0 - y) * c10 + (1.0 - x) * y * c01 + x * y * c11);
        at(i, j) = static_cast<std::int32_t>(out.nodes.size());
        out.nodes.push_back(q);
      }
    }
    for (std::size_t j = 0; j + 1 < nj; ++j) {
      for (std::size_t i = 0; i + 1 < ni; ++i) out.quads.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  // Boundary segments along the loop, each on the curve that holds its middle.
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    const Edge& e = edges_[i];
    if (!e.boundary) continue;
    // Nodes and their loop coordinates in the edge's canonical direction, then along the loop.
    auto ids = side_nodes({static_cast<int>(i), true});
    const auto& f = u[static_cast<std::size_t>(e.klass)];
    const std::size_t cells = f.size() - 1;
    std::vector<double> at(cells + 1);
    for (std::size_t j = 0; j <= cells; ++j) {
      const double t = e.flipped ? 1.0 - f[cells - j] : f[j];
      at[j] = e.s0 + t * (e.s1 - e.s0);
    }
    if (!e.loop_forward) {
      std::reverse(ids.begin(), ids.end());
      std::reverse(at.begin(), at.end());
    }
    for (std::size_t j = 0; j < cells; ++j) {
      const double s = std::fmod(0.5 * (at[j] + at[j + 1]), curve_start_.back());
      const auto it = std::upper_bound(curve_start_.begin(), curve_start_.end(), s);
      const auto curve = std::min(static_cast<std::size_t>(it - curve_start_.begin()) - 1, layout_.loop.size() - 1);
      out.boundary.push_back({ids[j], ids[j + 1], static_cast<int>(curve)});
    }
  }
  return out;
}

}  // namespace hotmesh::samples
