// hotmesh sample tool: how well a deformed mesh's wall follows its FEM deflection.
//
// Run:   build/samples/tools/wall_metrics DEFORMED.msh PATCH TABLE.csv [XMIN XMAX]
// Prints JSON: the patch's nodes, how many lie strictly between x = XMIN and XMAX (e.g. on a
// ramp between its corners), and the Hausdorff distance between the wall as the mesh
// discretises it (the polyline through the patch's nodes, in order along x) and the exact
// deflected wall (the polyline through the table's points Q_j + delta_j, in order along x).
// For polylines the distance is reached at a vertex of one of them, so vertices suffice.
// 2D meshes.
#include <algorithm>
#include <limits>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/deflection_csv.hpp"
#include "hotmesh/io/gmsh.hpp"

namespace {

struct P {
  double x, y;
};

double segment_distance(P p, P a, P b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double len2 = dx * dx + dy * dy;
  const double s = len2 > 0.0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(p.x - a.x - s * dx, p.y - a.y - s * dy);
}

double polyline_distance(P p, const std::vector<P>& line) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < line.size(); ++i) best = std::min(best, segment_distance(p, line[i], line[i + 1]));
  return best;
}

std::vector<P> sorted(std::vector<P> points) {
  std::sort(points.begin(), points.end(), [](P a, P b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  return points;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4 && argc != 6) {
    std::fprintf(stderr, "usage: wall_metrics DEFORMED.msh PATCH TABLE.csv [XMIN XMAX]\n");
    return 2;
  }
  try {
    const auto mesh = hotmesh::io::read_gmsh(argv[1]);
    const auto* patch = mesh.find_patch(argv[2]);
    if (!patch) throw hotmesh::InputError(fmt::format("{}: no patch '{}'", argv[1], argv[2]));
    const auto table = hotmesh::io::read_deflection_csv(argv[3]);
    std::vector<P> wall, exact;
    for (auto n : patch->nodes) wall.push_back({mesh.points[static_cast<std::size_t>(n)].x, mesh.points[static_cast<std::size_t>(n)].y});
    for (std::size_t j = 0; j < table.size(); ++j) {
      exact.push_back({table.points[j].x + table.deflections[j].x, table.points[j].y + table.deflections[j].y});
    }
    wall = sorted(wall);
    exact = sorted(exact);
    double hausdorff = 0.0;
    for (P p : wall) hausdorff = std::max(hausdorff, polyline_distance(p, exact));
    for (P p : exact) hausdorff = std::max(hausdorff, polyline_distance(p, wall));
    std::size_t between = 0;
    if (argc == 6) {
      const double lo = std::stod(argv[4]), hi = std::stod(argv[5]);
      between = static_cast<std::size_t>(std::count_if(wall.begin(), wall.end(), [&](P p) { return p.x > lo && p.x < hi; }));
    }
    std::printf("{\"nodes\": %zu, \"nodes_between\": %zu, \"max_distance_to_exact_wall\": %.6g}\n", wall.size(), between,
                hausdorff);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "wall_metrics: %s\n", e.what());
    return 2;
  }
}
