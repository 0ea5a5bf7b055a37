#include "test_support.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>

#include "hotmesh/mesh/split_cells.hpp"
#include "hotmesh/mesh/structured_mesh.hpp"

namespace hotmesh::test {

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  path_ = std::filesystem::temp_directory_path() /
          ("hotmesh-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

std::filesystem::path data_path(std::string_view name) { return std::filesystem::path(HOTMESH_TEST_DATA) / name; }

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_text(const std::filesystem::path& path, std::string_view text) {
  std::ofstream out(path, std::ios::binary);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

mesh::Mesh unit_square(int nx, int ny) {
  const auto xs = mesh::uniform_line(0.0, 1.0, nx);
  const auto ys = mesh::uniform_line(0.0, 1.0, ny);
  return mesh::structured_quads(xs, ys);
}

mesh::Mesh unit_cube(int n) {
  const auto line = mesh::uniform_line(0.0, 1.0, n);
  return mesh::structured_hexes(line, line, line);
}

mesh::Mesh square_ring(int per_side, int radial, double inner, double outer, int layers, double depth,
                         double growth) {
  using mesh::ElementType;
  using mesh::NodeId;
  const int around = 4 * per_side;
  // Point at perimeter position j (0..around) of the square with half side h, counter-clockwise
  // from (h, -h).
  auto on_square = [per_side](int j, double h) {
    const int side = (j / per_side) % 4;
    const double s = -h + 2.0 * h * (j % per_side) / per_side;
    switch (side) {
      case 0: return geometry::Vec3{h, s, 0};
      case 1: return geometry::Vec3{-s, h, 0};
      case 2: return geometry::Vec3{-h, -s, 0};
      default: return geometry::Vec3{s, -h, 0};
    }
  };
  mesh::Mesh ring;
  ring.dimension = 2;
  const auto half_sides = mesh::geometric_line(inner, outer, radial, growth);
  for (int k = 0; k <= radial; ++k) {
    const double h = half_sides[static_cast<std::size_t>(k)];
    for (int j = 0; j < around; ++j) ring.points.push_back(on_square(j, h));
  }
  auto id = [around](int k, int j) { return static_cast<NodeId>(k * around + (j % around)); };
  for (int k = 0; k < radial; ++k) {
    for (int j = 0; j < around; ++j) ring.cells.add(ElementType::quad4, {id(k, j), id(k + 1, j), id(k + 1, j + 1), id(k, j + 1)});
  }
  ring.patches.resize(2);
  ring.patches[0].name = "inner";
  ring.patches[0].tag = 1;
  ring.patches[1].name = "outer";
  ring.patches[1].tag = 2;
  for (int j = 0; j < around; ++j) {
    ring.patches[0].faces.add(ElementType::line2, {id(0, j + 1), id(0, j)});
    ring.patches[1].faces.add(ElementType::line2, {id(radial, j), id(radial, j + 1)});
  }
  ring.derive_node_sets();
  if (layers == 0) return ring;

  mesh::Mesh mesh;
  mesh.dimension = 3;
  const auto plane = static_cast<NodeId>(ring.points.size());
  for (int l = 0; l <= layers; ++l) {
    for (geometry::Vec3 p : ring.points) mesh.points.push_back({p.x, p.y, depth * l / layers});
  }
  for (int l = 0; l < layers; ++l) {
    const NodeId lo = l * plane, hi = (l + 1) * plane;
    for (std::size_t c = 0; c < ring.cells.size(); ++c) {
      const auto q = ring.cells.nodes(c);
      mesh.cells.add(ElementType::hex8, {lo + q[0], lo + q[1], lo + q[2], lo + q[3], hi + q[0], hi + q[1], hi + q[2], hi + q[3]});
    }
  }
  const char* names[] = {"inner", "outer", "zmin", "zmax"};
  mesh.patches.resize(4);
  for (int p = 0; p < 4; ++p) {
    mesh.patches[static_cast<std::size_t>(p)].name = names[p];
    mesh.patches[static_cast<std::size_t>(p)].tag = p + 1;
  }
  for (int l = 0; l < layers; ++l) {
    const NodeId lo = l * plane, hi = (l + 1) * plane;
    for (int p = 0; p < 2; ++p) {
      const auto& edges = ring.patches[static_cast<std::size_t>(p)].faces;
      for (std::size_t e = 0; e < edges.size(); ++e) {
        const auto n = edges.nodes(e);
        mesh.patches[static_cast<std::size_t>(p)].faces.add(ElementType::quad4, {lo + n[0], lo + n[1], hi + n[1], hi + n[0]});
      }
    }
  }
  const NodeId top = layers * plane;
  for (std::size_t c = 0; c < ring.cells.size(); ++c) {
    const auto q = ring.cells.nodes(c);
    mesh.patches[2].faces.add(ElementType::quad4, {q[0], q[3], q[2], q[1]});
    mesh.patches[3].faces.add(ElementType::quad4, {top + q[0], top + q[1], top + q[2], top + q[3]});
  }
  mesh.derive_node_sets();
  return mesh;
}

mesh::Mesh hybrid_ring(int per_side, int radial, double inner, double outer, int layers, double depth, double growth,
                       int layer_rings) {
  const mesh::Mesh ring = square_ring(per_side, radial, inner, outer, layers, depth, growth);
  const auto around = static_cast<std::size_t>(4 * per_side);
  const std::size_t per_layer = around * static_cast<std::size_t>(radial);
  std::vector<mesh::CellSplit> split(ring.cell_count());
  for (std::size_t c = 0; c < split.size(); ++c) {
    const bool body_layer = (c % per_layer) / around < static_cast<std::size_t>(layer_rings);  // cells run ring by ring
    if (layers == 0) {
      split[c] = body_layer ? mesh::CellSplit::keep : mesh::CellSplit::triangles;
    } else {
      split[c] = body_layer ? mesh::CellSplit::prisms : mesh::CellSplit::tetrahedra;
    }
  }
  return mesh::split_cells(ring, split);
}

mesh::Mesh annular_sector(int nr, int nt, int nz, double r0, double r1, double z0, double z1, double angle_deg) {
  const auto rs = mesh::uniform_line(r0, r1, nr);
  const auto ts = mesh::uniform_line(0.0, angle_deg * 3.14159265358979323846 / 180.0, nt);
  const auto zs = mesh::uniform_line(z0, z1, nz);
  mesh::Mesh mesh = mesh::structured_hexes(rs, ts, zs, {"inner", "outer", "per_lo", "per_hi", "bottom", "top"});
  for (auto& p : mesh.points) p = {p.x * std::cos(p.y), p.x * std::sin(p.y), p.z};  // (r, theta, z) -> (x, y, z)
  return mesh;
}

void jiggle_interior(mesh::Mesh& mesh, double fraction) {
  std::vector<char> on_boundary(mesh.node_count(), 0);
  for (const auto& p : mesh.patches) {
    for (auto n : p.nodes) on_boundary[static_cast<std::size_t>(n)] = 1;
  }
  std::vector<double> shortest(mesh.node_count(), 1e300);
  for (std::size_t c = 0; c < mesh.cells.size(); ++c) {
    const auto nodes = mesh.cells.nodes(c);
    for (auto a : nodes) {
      for (auto b : nodes) {
        if (a != b) {
          const double d = distance(mesh.points[static_cast<std::size_t>(a)], mesh.points[static_cast<std::size_t>(b)]);
          shortest[static_cast<std::size_t>(a)] = std::min(shortest[static_cast<std::size_t>(a)], d);
        }
      }
    }
  }
  std::uint64_t state = 0x2545F4914F6CDD1Dull;
  auto uniform = [&state] {  // xorshift64*, in [-1, 1)
    state ^= state >> 12;
    state ^= state << 25;
    state ^= state >> 27;
    return static_cast<double>((state * 0x2545F4914F6CDD1Dull) >> 11) / 4503599627370496.0 - 1.0;
  };
  for (std::size_t n = 0; n < mesh.node_count(); ++n) {
    const double dx = uniform(), dy = uniform(), dz = uniform();
    if (on_boundary[n]) continue;
    const double r = fraction * shortest[n];
    mesh.points[n] += geometry::Vec3{r * dx, r * dy, mesh.dimension == 3 ? r * dz : 0.0};
  }
}

mesh::Mesh shuffled_nodes(const mesh::Mesh& mesh, unsigned seed) {
  std::vector<mesh::NodeId> number(mesh.node_count());
  std::iota(number.begin(), number.end(), mesh::NodeId{0});
  std::shuffle(number.begin(), number.end(), std::mt19937(seed));
  mesh::Mesh out;
  out.dimension = mesh.dimension;
  out.points.resize(mesh.points.size());
  for (std::size_t n = 0; n < number.size(); ++n) out.points[static_cast<std::size_t>(number[n])] = mesh.points[n];
  std::vector<mesh::NodeId> nodes;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    nodes.clear();
    for (mesh::NodeId n : mesh.cells.nodes(c)) nodes.push_back(number[static_cast<std::size_t>(n)]);
    out.cells.add(mesh.cells.type(c), nodes);
  }
  return out;
}

}  // namespace hotmesh::test
