// hotmesh sample stator_well: the multi-block quad mesher (see block_mesh.hpp).
#include "block_mesh.hpp"

#include "boundary_loop.hpp"

#include <algorithm>
#include <limits>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

#include <fmt/format.h>

namespace hotmesh::samples {

namespace {

constexpr int kFieldSamples = 4000;  // integration of the spacing field along a class

std::string where(const Vec2& p) { return fmt::format("({:.6g}, {:.6g})", p.x, p.y); }

template <typename T>
const T& at(const std::vector<T>& v, int i) {
  return v[static_cast<std::size_t>(i)];
}

/// Union-find with parity: parity(x) says whether x's direction is reversed relative to its root.
class ParityUnion {
 public:
  explicit ParityUnion(std::size_t n) : parent_(n), parity_(n, 0) { std::iota(parent_.begin(), parent_.end(), 0); }
  std::pair<std::size_t, int> find(std::size_t x) const {
    int p = 0;
    while (parent_[x] != x) {
      p ^= parity_[x];
      x = parent_[x];
    }
    return {x, p};
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

}  // namespace

BlockMesher::BlockMesher(BlockLayout layout, SpacingField field) : layout_(std::move(layout)), field_(field) {
  if (layout_.loop.empty() || layout_.blocks.empty()) throw std::invalid_argument("block layout: no loop or no blocks");
  if (!(field_.growth > 1.0 && field_.wall_spacing > 0.0 && field_.spacing >= field_.wall_spacing)) {
    throw std::invalid_argument("block layout: the spacing field needs growth > 1 and 0 < wall_spacing <= spacing");
  }
  loop_ = std::make_unique<BoundaryLoop>(layout_.loop);
  double size = loop_->length();
  for (const Vec2& v : layout_.vertices) size = std::max(size, norm(v));
  for (const Vec2& v : layout_.vertices) vertex_s_.push_back(loop_->locate(v, 1e-9 * size).value_or(-1.0));
  build_edges();
  find_boundary_spans();
  build_classes();
}

BlockMesher::BlockMesher(BlockMesher&&) noexcept = default;
BlockMesher::~BlockMesher() = default;

void BlockMesher::build_edges() {
  std::map<std::pair<int, int>, int> edge_of;
  block_sides_.resize(layout_.blocks.size());
  for (std::size_t b = 0; b < layout_.blocks.size(); ++b) {
    const auto& q = layout_.blocks[b];
    double area = 0.0;
    for (std::size_t k = 0; k < 4; ++k) {
      const Vec2& p = layout_.vertices.at(static_cast<std::size_t>(q[k]));
      const Vec2& n = layout_.vertices.at(static_cast<std::size_t>(q[(k + 1) % 4]));
      area += p.x * n.y - n.x * p.y;
    }
    if (!(area > 0.0)) throw std::invalid_argument(fmt::format("block {} is not counter-clockwise", b));
    const std::array<std::pair<int, int>, 4> sides{{{q[0], q[1]}, {q[1], q[2]}, {q[3], q[2]}, {q[0], q[3]}}};
    for (std::size_t k = 0; k < 4; ++k) {
      const auto [a, c] = sides[k];
      const auto key = std::minmax(a, c);
      const auto [it, fresh] = edge_of.try_emplace(key, static_cast<int>(edges_.size()));
      if (fresh) {
        edges_.push_back({key.first, key.second});
        uses_.push_back(0);
      }
      if (++uses_[static_cast<std::size_t>(it->second)] > 2) {
        throw std::invalid_argument(fmt::format("block {}: side {} - {} is used by three blocks", b,
                                                where(at(layout_.vertices, a)), where(at(layout_.vertices, c))));
      }
      block_sides_[b][k] = {it->second, a < c};
    }
  }
}

void BlockMesher::find_boundary_spans() {
  // A side used by one block is on the boundary: it runs along the loop, in the block's
  // counter-clockwise order, from one of its corners to the other.
  const double total = loop_->length();
  for (std::size_t b = 0; b < layout_.blocks.size(); ++b) {
    const auto& q = layout_.blocks[b];
    for (std::size_t k = 0; k < 4; ++k) {
      const int a = q[k], c = q[(k + 1) % 4];
      const Side side = block_sides_[b][k];  // the same edge as the side from q[k] to q[k + 1]
      Edge& e = edges_[static_cast<std::size_t>(side.edge)];
      if (at(uses_, side.edge) != 1) {
        e.length = distance(at(layout_.vertices, e.v0), at(layout_.vertices, e.v1));
        continue;
      }
      const double sa = at(vertex_s_, a), sc = at(vertex_s_, c);
      const std::string name =
          fmt::format("block {}: boundary side {} - {}", b, where(at(layout_.vertices, a)), where(at(layout_.vertices, c)));
      if (sa < 0.0 || sc < 0.0) throw std::invalid_argument(name + " has a corner off the loop");
      const double end = sc > sa ? sc : sc + total;
      if (end - sa > 0.5 * total) throw std::invalid_argument(name + " runs against the loop");
      e.boundary = true;
      e.loop_forward = a == e.v0;
      e.s0 = e.loop_forward ? sa : end;
      e.s1 = e.loop_forward ? end : sa;
      e.length = end - sa;
    }
  }
}

bool BlockMesher::meets_wall(const Edge& e, int end) const {
  const double s = at(vertex_s_, end == 0 ? e.v0 : e.v1);
  if (s < 0.0) return false;
  auto walls = loop_->walls_at(s);
  if (e.boundary) {  // leave out the wall the side itself runs along, next to this end
    const bool leaving = (end == 0) == e.loop_forward;  // the loop leaves the vertex along the side
    const int own = loop_->wall(leaving ? loop_->curve_after(s) : loop_->curve_before(s));
    walls.erase(std::remove(walls.begin(), walls.end(), own), walls.end());
  }
  return !walls.empty();
}

void BlockMesher::build_classes() {
  // Opposite sides of a block carry the same count: chains of them form the classes.
  ParityUnion chains(edges_.size());
  for (std::size_t b = 0; b < block_sides_.size(); ++b) {
    const auto& s = block_sides_[b];
    for (const auto& [i, j] : {std::pair<std::size_t, std::size_t>{0, 2}, std::pair<std::size_t, std::size_t>{3, 1}}) {
      if (!chains.unite(static_cast<std::size_t>(s[i].edge), static_cast<std::size_t>(s[j].edge), s[i].forward == s[j].forward ? 0 : 1)) {
        throw std::invalid_argument(fmt::format("block {}: node counts cannot match (inconsistent orientation)", b));
      }
    }
  }
  std::map<std::size_t, int> class_of_root;
  std::vector<std::array<bool, 2>> clustered;
  std::vector<int> members;
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    const auto [root, parity] = chains.find(i);
    const auto [it, fresh] = class_of_root.try_emplace(root, static_cast<int>(classes_.size()));
    if (fresh) {
      classes_.emplace_back();
      clustered.push_back({false, false});
      members.push_back(0);
    }
    Edge& e = edges_[i];
    e.klass = it->second;
    e.flipped = parity != 0;
    const auto k = static_cast<std::size_t>(e.klass);
    classes_[k].length += e.length;
    ++members[k];
    for (int end = 0; end < 2; ++end) {
      if (meets_wall(e, end)) clustered[k][static_cast<std::size_t>(end ^ (e.flipped ? 1 : 0))] = true;
    }
  }
  // The cells of the spacing field along each class, from its reference start, at refinement 1
  // (Simpson's rule on 1 / h).
  for (std::size_t k = 0; k < classes_.size(); ++k) {
    Class& c = classes_[k];
    c.length /= members[k];
    const auto h = [&](double x) {
      double d = std::numeric_limits<double>::infinity();
      if (clustered[k][0]) d = std::min(d, x);
      if (clustered[k][1]) d = std::min(d, c.length - x);
      return std::min(field_.spacing, field_.wall_spacing + (field_.growth - 1.0) * d);
    };
    c.u.assign(kFieldSamples + 1, 0.0);
    c.cells.assign(kFieldSamples + 1, 0.0);
    for (std::size_t i = 1; i <= kFieldSamples; ++i) {
      const double a = c.length * static_cast<double>(i - 1) / kFieldSamples, b = c.length * static_cast<double>(i) / kFieldSamples;
      c.u[i] = static_cast<double>(i) / kFieldSamples;
      c.cells[i] = c.cells[i - 1] + (b - a) * (1.0 / h(a) + 4.0 / h(0.5 * (a + b)) + 1.0 / h(b)) / 6.0;
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
        out.nodes.push_back(loop_->point(e.s0 + t * (e.s1 - e.s0)));
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
    out.blocks.push_back({ni, nj, std::move(grid)});
  }
  // Boundary segments along the loop, each on the curve that holds its middle.
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    const Edge& e = edges_[i];
    if (!e.boundary) continue;
    // Nodes and their loop coordinates in the edge's canonical direction, then along the loop.
    auto ids = side_nodes({static_cast<int>(i), true});
    const auto& f = u[static_cast<std::size_t>(e.klass)];
    const std::size_t cells = f.size() - 1;
    std::vector<double> along(cells + 1);
    for (std::size_t j = 0; j <= cells; ++j) {
      const double t = e.flipped ? 1.0 - f[cells - j] : f[j];
      along[j] = e.s0 + t * (e.s1 - e.s0);
    }
    if (!e.loop_forward) {
      std::reverse(ids.begin(), ids.end());
      std::reverse(along.begin(), along.end());
    }
    for (std::size_t j = 0; j < cells; ++j) {
      const double middle = 0.5 * (along[j] + along[j + 1]);
      out.boundary.push_back({ids[j], ids[j + 1], static_cast<int>(loop_->curve_after(middle))});
    }
  }
  return out;
}

}  // namespace hotmesh::samples
