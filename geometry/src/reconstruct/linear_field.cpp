// hotmesh geometry: linear interpolation of a wall's table over a Delaunay triangulation of its
// nodes in their mean plane (linear_field.hpp). CGAL triangulates; the triangles are then kept
// in a uniform grid over the plane, so an evaluation reads immutable arrays only (thread-safe)
// and costs the few triangles of a cell or two.
#include "hotmesh/geometry/linear_field.hpp"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>

#include "hotmesh/core/input_error.hpp"
#include "reconstruct/scattered_samples.hpp"

namespace hotmesh::geometry {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, Kernel>;
using Delaunay =
    CGAL::Delaunay_triangulation_2<Kernel, CGAL::Triangulation_data_structure_2<VertexBase, CGAL::Triangulation_face_base_2<Kernel>>>;

constexpr double kPi = 3.14159265358979323846;

std::string text(const Vec3& v) {
  std::ostringstream out;
  out.precision(9);
  out << '(' << v.x << ", " << v.y << ", " << v.z << ')';
  return out.str();
}

struct Point2 {
  double u = 0.0, v = 0.0;
};

/// The closest point of segment ab to q, as the fraction t along it, and its squared distance.
double segment_distance2(const Point2& q, const Point2& a, const Point2& b, double& t) {
  const double du = b.u - a.u, dv = b.v - a.v;
  const double length2 = du * du + dv * dv;
  t = length2 > 0.0 ? std::clamp(((q.u - a.u) * du + (q.v - a.v) * dv) / length2, 0.0, 1.0) : 0.0;
  const double eu = a.u + t * du - q.u, ev = a.v + t * dv - q.v;
  return eu * eu + ev * ev;
}

}  // namespace

struct LinearField::Impl {
  Vec3 centroid;
  std::array<Vec3, 2> plane;  ///< the plane's two directions
  std::vector<Point2> points;
  std::vector<Vec3> values;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  // the grid: cells of `cell` x `cell` from `origin`, columns x rows; triangles by cell (CSR)
  Point2 origin;
  double cell = 1.0;
  int columns = 1, rows = 1;
  std::vector<std::uint32_t> cell_start, cell_triangles;

  Point2 project(const Vec3& x) const {
    const Vec3 d = x - centroid;
    return {dot(d, plane[0]), dot(d, plane[1])};
  }

  /// Barycentric coordinates of q in triangle t (inside: all >= 0).
  std::array<double, 3> barycentric(const Point2& q, std::uint32_t t) const {
    const Point2 &a = points[triangles[t][0]], &b = points[triangles[t][1]], &c = points[triangles[t][2]];
    const double det = (b.u - a.u) * (c.v - a.v) - (c.u - a.u) * (b.v - a.v);
    const double l1 = ((q.u - a.u) * (c.v - a.v) - (c.u - a.u) * (q.v - a.v)) / det;
    const double l2 = ((b.u - a.u) * (q.v - a.v) - (q.u - a.u) * (b.v - a.v)) / det;
    return {1.0 - l1 - l2, l1, l2};
  }

  /// Squared distance from q to triangle t and the barycentric coordinates of its closest point.
  double distance2(const Point2& q, std::uint32_t t, std::array<double, 3>& weights) const {
    weights = barycentric(q, t);
    if (weights[0] >= 0.0 && weights[1] >= 0.0 && weights[2] >= 0.0) return 0.0;
    double best = std::numeric_limits<double>::infinity();
    for (int e = 0; e < 3; ++e) {
      const auto i = static_cast<std::size_t>(e), j = static_cast<std::size_t>((e + 1) % 3);
      double along = 0.0;
      const double d2 = segment_distance2(q, points[triangles[t][i]], points[triangles[t][j]], along);
      if (d2 < best) {
        best = d2;
        weights = {0.0, 0.0, 0.0};
        weights[i] = 1.0 - along;
        weights[j] = along;
      }
    }
    return best;
  }

  /// The triangle holding q, or the nearest one: rings of cells around q's cell until no
  /// farther cell can hold a nearer triangle. Returns the squared distance.
  double locate(const Point2& q, std::uint32_t& found, std::array<double, 3>& weights) const {
    const int ci = std::clamp(static_cast<int>(std::floor((q.u - origin.u) / cell)), 0, columns - 1);
    const int cj = std::clamp(static_cast<int>(std::floor((q.v - origin.v) / cell)), 0, rows - 1);
    double best = std::numeric_limits<double>::infinity();
    for (int ring = 0; ring <= std::max(columns, rows); ++ring) {
      for (int j = cj - ring; j <= cj + ring; ++j) {
        for (int i = ci - ring; i <= ci + ring; ++i) {
          if (i < 0 || j < 0 || i >= columns || j >= rows) continue;
          if (std::max(std::abs(i - ci), std::abs(j - cj)) != ring) continue;
          const auto c = static_cast<std::size_t>(j) * static_cast<std::size_t>(columns) + static_cast<std::size_t>(i);
          for (std::uint32_t k = cell_start[c]; k < cell_start[c + 1]; ++k) {
            std::array<double, 3> w{};
            const double d2 = distance2(q, cell_triangles[k], w);
            if (d2 < best) {
              best = d2;
              found = cell_triangles[k];
              weights = w;
              if (d2 == 0.0) return 0.0;
            }
          }
        }
      }
      // every cell of the next ring lies at least ring * cell from q
      if (best <= (ring * cell) * (ring * cell)) break;
    }
    return best;
  }

  void build_grid();
};

void LinearField::Impl::build_grid() {
  Point2 lo = points.front(), hi = points.front();
  for (const Point2& p : points) {
    lo = {std::min(lo.u, p.u), std::min(lo.v, p.v)};
    hi = {std::max(hi.u, p.u), std::max(hi.v, p.v)};
  }
  const double width = hi.u - lo.u, height = hi.v - lo.v;
  // about two triangles per cell
  cell = std::sqrt(std::max(width * height, 1e-300) / std::max<double>(1.0, 0.5 * static_cast<double>(triangles.size())));
  cell = std::max(cell, 1e-9 * std::max(width, height));
  origin = lo;
  columns = std::clamp(static_cast<int>(std::ceil(width / cell)), 1, 4096);
  rows = std::clamp(static_cast<int>(std::ceil(height / cell)), 1, 4096);
  cell = std::max(width / columns, height / rows) * (1.0 + 1e-12);
  const auto cell_range = [&](std::uint32_t t, std::array<int, 4>& range) {
    Point2 a = points[triangles[t][0]], b = a;
    for (std::uint32_t n : triangles[t]) {
      a = {std::min(a.u, points[n].u), std::min(a.v, points[n].v)};
      b = {std::max(b.u, points[n].u), std::max(b.v, points[n].v)};
    }
    range = {std::clamp(static_cast<int>(std::floor((a.u - origin.u) / cell)), 0, columns - 1),
             std::clamp(static_cast<int>(std::floor((b.u - origin.u) / cell)), 0, columns - 1),
             std::clamp(static_cast<int>(std::floor((a.v - origin.v) / cell)), 0, rows - 1),
             std::clamp(static_cast<int>(std::floor((b.v - origin.v) / cell)), 0, rows - 1)};
  };
  const auto cells = static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows);
  cell_start.assign(cells + 1, 0);
  std::array<int, 4> r{};
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<std::uint32_t> next(cell_start.begin(), cell_start.end() - 1);
    if (pass == 1) cell_triangles.resize(cell_start.back());
    for (std::uint32_t t = 0; t < triangles.size(); ++t) {
      cell_range(t, r);
      for (int j = r[2]; j <= r[3]; ++j) {
        for (int i = r[0]; i <= r[1]; ++i) {
          const auto c = static_cast<std::size_t>(j) * static_cast<std::size_t>(columns) + static_cast<std::size_t>(i);
          if (pass == 0) {
            ++cell_start[c + 1];
          } else {
            cell_triangles[next[c]++] = t;
          }
        }
      }
    }
    if (pass == 0) {
      for (std::size_t c = 0; c < cells; ++c) cell_start[c + 1] += cell_start[c];
    }
  }
}

LinearField::LinearField(std::vector<Vec3> sample_points, std::vector<Vec3> sample_values, double max_tilt_deg) {
  const ScatteredFieldOptions options;
  report_.samples = sample_points.size();
  DistinctSamples distinct = distinct_finite_samples(std::move(sample_points), std::move(sample_values), options);
  report_.points = distinct.points.size();
  report_.merged_duplicates = distinct.merged;
  const std::vector<Vec3>& xyz = distinct.points;
  std::vector<std::uint32_t> all(xyz.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<std::uint32_t>(i);
  const Hull hull = xyz.size() < 3 ? Hull{} : affine_hull(xyz, all, options.flatness, rounding(xyz, options));
  if (hull.dimension < 2) {
    throw InputError("linear interpolation over a wall: needs at least 3 distinct table nodes not on one line, got " +
                     std::to_string(xyz.size()) + " distinct nodes");
  }
  auto impl = std::make_shared<Impl>();
  impl->centroid = hull.centroid;
  impl->plane = {hull.axes[0], hull.axes[1]};
  impl->values = std::move(distinct.values);

  Delaunay delaunay;
  Delaunay::Vertex_handle hint;
  for (std::uint32_t i = 0; i < xyz.size(); ++i) {
    impl->points.push_back(impl->project(xyz[i]));
    const std::size_t before = delaunay.number_of_vertices();
    hint = delaunay.insert(Kernel::Point_2(impl->points[i].u, impl->points[i].v), hint == nullptr ? Delaunay::Face_handle() : hint->face());
    if (delaunay.number_of_vertices() == before) {
      throw InputError("linear interpolation over a wall: table nodes " + text(xyz[hint->info()]) + " and " + text(xyz[i]) +
                       " lie over one point of the table's mean plane: the wall folds over it (give its CAD faces, "
                       "or degree 2 or more for the smooth interpolation)");
    }
    hint->info() = i;
  }
  const Vec3 normal = cross(hull.axes[0], hull.axes[1]);
  const double max_cos = std::cos(max_tilt_deg * kPi / 180.0);
  for (auto f = delaunay.finite_faces_begin(); f != delaunay.finite_faces_end(); ++f) {
    const std::array<std::uint32_t, 3> t{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};
    impl->triangles.push_back(t);
    const Vec3 n = cross(xyz[t[1]] - xyz[t[0]], xyz[t[2]] - xyz[t[0]]);
    const double cosine = std::abs(dot(n, normal)) / std::max(norm(n), std::numeric_limits<double>::min());
    bool on_hull = false;  // slivers along the convex hull may stand at any angle
    for (int k = 0; k < 3; ++k) on_hull = on_hull || delaunay.is_infinite(f->neighbor(k));
    if (on_hull) continue;
    report_.max_tilt_deg = std::max(report_.max_tilt_deg, std::acos(std::min(1.0, cosine)) * 180.0 / kPi);
    if (cosine < max_cos) {
      throw InputError("linear interpolation over a wall: the triangle of table nodes " + text(xyz[t[0]]) + ", " +
                       text(xyz[t[1]]) + " and " + text(xyz[t[2]]) + " stands at " +
                       std::to_string(std::acos(cosine) * 180.0 / kPi) + " degrees to the nodes' mean plane (more than " +
                       std::to_string(max_tilt_deg) + "): the wall is not a graph over one plane (give its CAD faces, "
                       "or degree 2 or more for the smooth interpolation)");
    }
  }
  report_.triangles = impl->triangles.size();
  if (impl->triangles.empty()) {
    throw InputError("linear interpolation over a wall: the table's nodes make no triangle");
  }
  impl->build_grid();
  impl_ = std::move(impl);
}

Vec3 LinearField::operator()(const Vec3& x) const {
  if (!is_finite(x)) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan};
  }
  std::uint32_t t = 0;
  std::array<double, 3> w{};
  impl_->locate(impl_->project(x), t, w);
  const auto& nodes = impl_->triangles[t];
  return w[0] * impl_->values[nodes[0]] + w[1] * impl_->values[nodes[1]] + w[2] * impl_->values[nodes[2]];
}

double LinearField::outside(const Vec3& x) const {
  std::uint32_t t = 0;
  std::array<double, 3> w{};
  const double beyond = std::sqrt(impl_->locate(impl_->project(x), t, w));
  if (beyond == 0.0) return 0.0;
  double size = 0.0;  // the nearest triangle's longest edge
  for (int e = 0; e < 3; ++e) {
    const Point2& a = impl_->points[impl_->triangles[t][static_cast<std::size_t>(e)]];
    const Point2& b = impl_->points[impl_->triangles[t][static_cast<std::size_t>((e + 1) % 3)]];
    size = std::max(size, std::hypot(b.u - a.u, b.v - a.v));
  }
  return std::max(0.0, beyond - size);
}

}  // namespace hotmesh::geometry
