#include "hotmesh/mesh/structured_mesh.hpp"

#include <cmath>
#include <stdexcept>

namespace hotmesh::mesh {
namespace {

void check_line(std::span<const double> line, const char* what) {
  if (line.size() < 2) throw std::invalid_argument(std::string(what) + ": need at least two coordinates");
  for (std::size_t i = 1; i < line.size(); ++i) {
    if (!(line[i] > line[i - 1])) throw std::invalid_argument(std::string(what) + ": must increase strictly");
  }
}

Patch make_patch(const std::string& name, int tag) {
  Patch p;
  p.name = name;
  p.tag = tag;
  return p;
}

}  // namespace

Mesh structured_quads(std::span<const double> xs, std::span<const double> ys,
                      const std::array<std::string, 4>& names) {
  check_line(xs, "xs");
  check_line(ys, "ys");
  const auto nx = static_cast<NodeId>(xs.size());
  const auto ny = static_cast<NodeId>(ys.size());
  auto id = [nx](NodeId i, NodeId j) { return j * nx + i; };
  Mesh mesh;
  mesh.dimension = 2;
  mesh.points.reserve(xs.size() * ys.size());
  for (double y : ys) {
    for (double x : xs) mesh.points.push_back({x, y, 0.0});
  }
  mesh.cells.reserve(static_cast<std::size_t>((nx - 1) * (ny - 1)), static_cast<std::size_t>(4 * (nx - 1) * (ny - 1)));
  for (NodeId j = 0; j + 1 < ny; ++j) {
    for (NodeId i = 0; i + 1 < nx; ++i) {
      mesh.cells.add(ElementType::quad4, {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  for (int s = 0; s < 4; ++s) mesh.patches.push_back(make_patch(names[static_cast<std::size_t>(s)], s + 1));
  for (NodeId j = 0; j + 1 < ny; ++j) {
    mesh.patches[0].faces.add(ElementType::line2, {id(0, j + 1), id(0, j)});
    mesh.patches[1].faces.add(ElementType::line2, {id(nx - 1, j), id(nx - 1, j + 1)});
  }
  for (NodeId i = 0; i + 1 < nx; ++i) {
    mesh.patches[2].faces.add(ElementType::line2, {id(i, 0), id(i + 1, 0)});
    mesh.patches[3].faces.add(ElementType::line2, {id(i + 1, ny - 1), id(i, ny - 1)});
  }
  mesh.derive_node_sets();
  return mesh;
}

Mesh structured_hexes(std::span<const double> xs, std::span<const double> ys, std::span<const double> zs,
                      const std::array<std::string, 6>& names) {
  check_line(xs, "xs");
  check_line(ys, "ys");
  check_line(zs, "zs");
  const auto nx = static_cast<NodeId>(xs.size());
  const auto ny = static_cast<NodeId>(ys.size());
  const auto nz = static_cast<NodeId>(zs.size());
  auto id = [nx, ny](NodeId i, NodeId j, NodeId k) { return (k * ny + j) * nx + i; };
  Mesh mesh;
  mesh.dimension = 3;
  mesh.points.reserve(xs.size() * ys.size() * zs.size());
  for (double z : zs) {
    for (double y : ys) {
      for (double x : xs) mesh.points.push_back({x, y, z});
    }
  }
  const auto cells = static_cast<std::size_t>((nx - 1) * (ny - 1) * (nz - 1));
  mesh.cells.reserve(cells, 8 * cells);
  for (NodeId k = 0; k + 1 < nz; ++k) {
    for (NodeId j = 0; j + 1 < ny; ++j) {
      for (NodeId i = 0; i + 1 < nx; ++i) {
        mesh.cells.add(ElementType::hex8, {id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                                           id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1),
                                           id(i, j + 1, k + 1)});
      }
    }
  }
  for (int s = 0; s < 6; ++s) mesh.patches.push_back(make_patch(names[static_cast<std::size_t>(s)], s + 1));
  // Faces oriented outward (right-hand normal), matching the cells' own faces.
  for (NodeId k = 0; k + 1 < nz; ++k) {
    for (NodeId j = 0; j + 1 < ny; ++j) {
      mesh.patches[0].faces.add(ElementType::quad4, {id(0, j, k), id(0, j, k + 1), id(0, j + 1, k + 1), id(0, j + 1, k)});
      const NodeId i = nx - 1;
      mesh.patches[1].faces.add(ElementType::quad4, {id(i, j, k), id(i, j + 1, k), id(i, j + 1, k + 1), id(i, j, k + 1)});
    }
  }
  for (NodeId k = 0; k + 1 < nz; ++k) {
    for (NodeId i = 0; i + 1 < nx; ++i) {
      mesh.patches[2].faces.add(ElementType::quad4, {id(i, 0, k), id(i + 1, 0, k), id(i + 1, 0, k + 1), id(i, 0, k + 1)});
      const NodeId j = ny - 1;
      mesh.patches[3].faces.add(ElementType::quad4, {id(i, j, k), id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j, k)});
    }
  }
  for (NodeId j = 0; j + 1 < ny; ++j) {
    for (NodeId i = 0; i + 1 < nx; ++i) {
      mesh.patches[4].faces.add(ElementType::quad4, {id(i, j, 0), id(i, j + 1, 0), id(i + 1, j + 1, 0), id(i + 1, j, 0)});
      const NodeId k = nz - 1;
      mesh.patches[5].faces.add(ElementType::quad4, {id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k)});
    }
  }
  mesh.derive_node_sets();
  return mesh;
}

std::vector<double> uniform_line(double a, double b, int n) {
  return geometric_line(a, b, n, 1.0);
}

std::vector<double> geometric_line(double a, double b, int n, double ratio) {
  if (n < 1 || !(ratio > 0.0)) throw std::invalid_argument("geometric_line: need n >= 1 and ratio > 0");
  std::vector<double> line(static_cast<std::size_t>(n) + 1);
  double total = 0.0, h = 1.0;
  for (int i = 0; i < n; ++i, h *= ratio) total += h;
  double s = 0.0;
  h = 1.0;
  line[0] = a;
  for (int i = 1; i <= n; ++i, h *= ratio) {
    s += h;
    line[static_cast<std::size_t>(i)] = a + (b - a) * s / total;
  }
  line.back() = b;
  return line;
}

std::vector<double> stretched_line(double a, double b, int n, double first_spacing) {
  const double length = b - a;
  if (n < 1 || !(first_spacing > 0.0) || !(first_spacing * n < length)) {
    throw std::invalid_argument("stretched_line: need 0 < first_spacing < (b - a) / n");
  }
  // Total length first * (r^n - 1) / (r - 1) grows with r: bisect for r in (1, rmax].
  auto total = [&](double r) {
    double sum = 0.0, h = first_spacing;
    for (int i = 0; i < n; ++i, h *= r) sum += h;
    return sum;
  };
  double lo = 1.0, hi = 2.0;
  while (total(hi) < length) hi *= 2.0;
  for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (total(mid) < length ? lo : hi) = mid;
  }
  return geometric_line(a, b, n, 0.5 * (lo + hi));
}

}  // namespace hotmesh::mesh
