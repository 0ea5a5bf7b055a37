// hotmesh sample: two parallel walls in relative tangential motion, the paper's Fig. 1-a.
//
// What it shows: a channel of height h between two walls; the upper wall moves along itself
// by h, as far as the walls are apart. If the wall nodes must follow the walls' material
// points, every cell across the channel is sheared by 45 degrees; if they may slide along
// the walls (section 4), the nodes redistribute and the cells stay much closer to square,
// except near the channel's ends, which are held by the inlet and outlet.
//
// Run:   build/samples/shear2d/make_shear2d [OUTPUT_FOLDER]   (default: the current folder)
// Writes shear2d.msh (the undeformed mesh, Gmsh 4.1) and the FEM tables top.csv (the moving
// wall), inlet.csv and outlet.csv (the channel's ends, sheared linearly between the walls).
// The committed copies in samples/shear2d/ are this program's output.
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

// 1. The channel: length 6h, height h (h = 1); the upper wall moves by kShift = h along x.
constexpr double kLength = 6.0;
constexpr double kHeight = 1.0;
constexpr double kShift = 1.0;

// 2. The mesh: 60 uniform cells along x, 24 across, clustered towards both walls (first
// cell 0.01 h, growing geometrically to the middle).
constexpr int kCellsX = 60;
constexpr int kCellsHalfY = 12;
constexpr double kFirstCellY = 0.01;

std::vector<double> clustered_height() {
  const auto half = hotmesh::mesh::stretched_line(0.0, 0.5 * kHeight, kCellsHalfY, kFirstCellY);
  std::vector<double> ys = half;
  for (auto it = half.rbegin() + 1; it != half.rend(); ++it) ys.push_back(kHeight - *it);
  return ys;
}

/// 3. The FEM tables: the upper wall translates by kShift; the ends shear linearly, so the
/// channel's corners follow the walls they belong to.
std::string wall_table() {
  std::string csv = "# hotmesh sample shear2d: the upper wall moves along itself by h\nx,y,dx,dy\n";
  for (int i = 0; i <= 30; ++i) csv += fmt::format("{},{},{},0\n", kLength * i / 30.0, kHeight, kShift);
  return csv;
}

std::string end_table(double x) {
  std::string csv = fmt::format("# hotmesh sample shear2d: the channel end at x = {}, sheared between the walls\nx,y,dx,dy\n", x);
  for (int j = 0; j <= 10; ++j) csv += fmt::format("{},{},{},0\n", x, kHeight * j / 10.0, kShift * j / 10.0);
  return csv;
}

}  // namespace

int main(int argc, char** argv) {
  return hotmesh::samples::run_generator("make_shear2d", argc, argv, [](const std::filesystem::path& folder) {
    const auto xs = hotmesh::mesh::uniform_line(0.0, kLength, kCellsX);
    const auto mesh = hotmesh::mesh::structured_quads(xs, clustered_height(), {"inlet", "outlet", "bottom", "top"});
    hotmesh::io::write_gmsh(folder / "shear2d.msh", mesh);
    hotmesh::io::write_file_atomically(folder / "top.csv", wall_table());
    hotmesh::io::write_file_atomically(folder / "inlet.csv", end_table(0.0));
    hotmesh::io::write_file_atomically(folder / "outlet.csv", end_table(kLength));
    std::printf("wrote shear2d.msh, top.csv, inlet.csv and outlet.csv in %s\n", folder.c_str());
  });
}
