// hotmesh sample: a bump with two shoulders, a second steep shape beside the paper's ramp
// (section 5), with its deflected wall known exactly.
//
// What it shows: a deflection with four corners. In a channel of height h and length 3h the
// lower wall is pushed up into a trapezoidal bump of height 0.3 h: it rises over 0.1 h (a flank
// of 71.6 degrees), runs flat for 0.4 h and falls over 0.1 h. Its feet A and D are concave
// corners, its shoulders B and C convex ones. The mesh has a uniform axial spacing
// dx = 3h/86 = 0.0349 h, so each flank is 2.87 cells wide, and no corner lies on a mesh node
// (step 2 gives by how much). The mesh is strongly stretched towards the lower wall, as a
// boundary-layer mesh would be (the same stretching as ramp2d).
//
// Run:   build/samples/step2d/make_step2d [OUTPUT_FOLDER]   (default: the current folder)
// Writes step2d.msh (the undeformed mesh, Gmsh 4.1) and bump.csv (the FEM deflection table of
// the lower wall). The committed copies in samples/step2d/ are this program's output.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "hotmesh/mesh/structured_mesh.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "sample_generator.hpp"

namespace {

// 1. The geometry, in units of the channel height h. The bump is centred in the channel.
constexpr double kHeight = 1.0;                  // h
constexpr double kLength = 3.0 * kHeight;        // 3h
constexpr double kBumpHeight = 0.3 * kHeight;    // 0.3 h
// The four corners of the deflected wall, along x: foot A (concave), shoulder B (convex),
// shoulder C (convex), foot D (concave). Each flank rises (falls) over 0.1 h; the flat top
// between the shoulders is 0.4 h long.
constexpr double kFootA = 1.2 * kHeight;
constexpr double kShoulderB = 1.3 * kHeight;
constexpr double kShoulderC = 1.7 * kHeight;
constexpr double kFootD = 1.8 * kHeight;
constexpr std::array<double, 4> kCorners = {kFootA, kShoulderB, kShoulderC, kFootD};

// 2. The mesh: 86 uniform cells along x (dx = 3h/86 = 0.03488 h) and 40 cells across, growing
// geometrically from a first cell of 0.001 h at the lower wall (aspect ratio 35 there, about
// 13% growth per cell). With 86 cells the corners fall between nodes: A = 1.2 h is 0.40 dx past
// node 34, B = 1.3 h 0.27 dx past node 37, C = 1.7 h 0.27 dx before node 49 and D = 1.8 h
// 0.40 dx before node 52 (the mesh and the bump are both symmetric about x = 1.5 h). Nodes
// 35-37 lie on the rising flank, 38-48 on the top, 49-51 on the falling flank.
constexpr int kCellsX = 86;
constexpr int kCellsY = 40;
constexpr double kFirstCellY = 0.001 * kHeight;

/// The lower wall's deflection: 0 outside the bump, 0.3 h on its top, linear on its flanks.
double bump_deflection(double x) {
  if (x <= kFootA || x >= kFootD) return 0.0;
  if (x < kShoulderB) return kBumpHeight * (x - kFootA) / (kShoulderB - kFootA);
  if (x > kShoulderC) return kBumpHeight * (kFootD - x) / (kFootD - kShoulderC);
  return kBumpHeight;
}

/// 3. The FEM table: FEM nodes every 0.01 h along the lower wall plus the four corners exactly
/// (where the 0.01 h grid meets a corner to within rounding, the corner replaces it). The
/// deflected wall is linear between these nodes, so the polyline through the deflected table
/// points Q_j + delta_j is the exact deflected wall.
std::string deflection_table() {
  std::vector<double> xs(kCorners.begin(), kCorners.end());
  for (int i = 0; i <= 300; ++i) {
    const double x = i / 100.0 * kHeight;
    if (std::none_of(kCorners.begin(), kCorners.end(), [x](double c) { return std::abs(x - c) < 1e-9; })) {
      xs.push_back(x);
    }
  }
  return hotmesh::samples::lower_wall_table(
      "# hotmesh sample step2d: deflection of the lower wall\n"
      "# a trapezoidal bump of height 0.3 h in the middle of a 3h x h channel, h = 1: feet at\n"
      "# x = 1.2 h and 1.8 h, shoulders at 1.3 h and 1.7 h; the polyline of x + dx, y + dy is exact\n",
      xs, bump_deflection);
}

}  // namespace

int main(int argc, char** argv) {
  return hotmesh::samples::run_generator("make_step2d", argc, argv, [](const std::filesystem::path& folder) {
    const auto xs = hotmesh::mesh::uniform_line(0.0, kLength, kCellsX);
    const auto ys = hotmesh::mesh::stretched_line(0.0, kHeight, kCellsY, kFirstCellY);
    const auto mesh = hotmesh::mesh::structured_quads(xs, ys, {"left", "right", "bottom", "top"});
    hotmesh::io::write_gmsh(folder / "step2d.msh", mesh);
    hotmesh::io::write_file_atomically(folder / "bump.csv", deflection_table());
    std::printf("wrote %s and %s\n", (folder / "step2d.msh").c_str(), (folder / "bump.csv").c_str());
  });
}
