// hotmesh sample: the 2D ramp of the paper's section 5 (Amirante, Hills & Barnes, Fig. 6).
//
// What it shows: a boundary deflection with a near-discontinuity. In a box of height h and
// length 2h the lower wall is folded into a ramp of height h/2 that rises over 0.05 h, while
// the mesh has a uniform axial spacing dx = 0.035 h: the ramp is narrower than two cells and
// its corners A and B fall between mesh nodes. The mesh is strongly stretched towards the
// lower wall, as a boundary-layer mesh would be.
//
// Run:   build/samples/ramp2d/make_ramp2d [--refine N] [OUTPUT_FOLDER]   (default: the current folder)
// Writes ramp2d.msh (the undeformed mesh, Gmsh 4.1) and ramp.csv (the FEM deflection table
// of the lower wall), and the same mesh with its quads split into triangles along a diagonal:
// all of them (ramp2d-triangles.msh), or those above the 8 rows of quads on the lower wall
// (ramp2d-hybrid.msh, a boundary layer of quads under triangles). The committed copies in
// samples/ramp2d/ are this program's output. With --refine N: ramp2d.msh N times finer in
// both directions (first cell 0.001 h / N) and ramp.csv only, for the size benchmarks of the
// linear solvers (scripts/bench.sh).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "hotmesh/mesh/split_cells.hpp"
#include "hotmesh/mesh/structured_mesh.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "sample_generator.hpp"

namespace {

// 1. The geometry of Fig. 6, in units of the channel height h.
constexpr double kHeight = 1.0;                    // h
constexpr double kLength = 2.0 * kHeight;          // 2h
constexpr double kRampHeight = 0.5 * kHeight;      // h/2
constexpr double kRampWidth = 0.05 * kHeight;      // the ramp rises over 0.05 h
constexpr double kRampStart = 0.5 * (kLength - kRampWidth);  // corner A (lower); B at A + 0.05 h

// 2. The mesh: 57 uniform cells along x (dx = 2h/57 = 0.0351 h, the paper's 0.035 h) and 40
// cells across, growing geometrically from a first cell of 0.001 h at the lower wall (aspect
// ratio 35 there, about 13% growth per cell).
constexpr int kCellsX = 57;
constexpr int kCellsY = 40;
constexpr double kFirstCellY = 0.001 * kHeight;
constexpr int kQuadRows = 8;  // the hybrid mesh's rows of quads on the lower wall

/// The lower wall's deflection: 0 before the ramp, h/2 after it, linear in between.
double ramp_deflection(double x) {
  if (x <= kRampStart) return 0.0;
  if (x >= kRampStart + kRampWidth) return kRampHeight;
  return kRampHeight * (x - kRampStart) / kRampWidth;
}

/// 3. The FEM table: FEM nodes every 0.01 h along the lower wall (finer than the CFD mesh)
/// plus the two ramp corners (the structural model knows where its wall folds; the CFD mesh
/// does not).
std::string deflection_table() {
  std::vector<double> xs;
  for (int i = 0; i <= 200; ++i) xs.push_back(0.01 * i * kHeight);
  xs.push_back(kRampStart);
  xs.push_back(kRampStart + kRampWidth);
  return hotmesh::samples::lower_wall_table(
      "# hotmesh sample ramp2d: deflection of the lower wall (paper's Fig. 6)\n"
      "# a ramp of height h/2 rising over 0.05 h in the middle of a 2h x h channel, h = 1\n",
      xs, ramp_deflection);
}

}  // namespace

int main(int argc, char** argv) {
  int refine = 1;
  if (argc > 2 && std::string_view(argv[1]) == "--refine") {
    refine = std::atoi(argv[2]);
    if (refine < 1 || refine > 64) {
      std::fprintf(stderr, "make_ramp2d: --refine takes an integer from 1 to 64, got '%s'\n", argv[2]);
      return 2;
    }
    argv[2] = argv[0];  // the rest as if without the option
    argc -= 2;
    argv += 2;
  }
  return hotmesh::samples::run_generator("make_ramp2d", argc, argv, [refine](const std::filesystem::path& folder) {
    const auto xs = hotmesh::mesh::uniform_line(0.0, kLength, kCellsX * refine);
    const auto ys = hotmesh::mesh::stretched_line(0.0, kHeight, kCellsY * refine, kFirstCellY / refine);
    const auto mesh = hotmesh::mesh::structured_quads(xs, ys, {"left", "right", "bottom", "top"});
    hotmesh::io::write_gmsh(folder / "ramp2d.msh", mesh);
    hotmesh::io::write_file_atomically(folder / "ramp.csv", deflection_table());
    if (refine > 1) {
      std::printf("wrote ramp2d.msh (refined %d times: %zu cells) and ramp.csv in %s\n", refine, mesh.cell_count(),
                  folder.c_str());
      return;
    }
    // Cells run row by row from the lower wall up.
    std::vector<hotmesh::mesh::CellSplit> split(mesh.cell_count(), hotmesh::mesh::CellSplit::triangles);
    hotmesh::io::write_gmsh(folder / "ramp2d-triangles.msh", hotmesh::mesh::split_cells(mesh, split));
    std::fill(split.begin(), split.begin() + kCellsX * kQuadRows, hotmesh::mesh::CellSplit::keep);
    hotmesh::io::write_gmsh(folder / "ramp2d-hybrid.msh", hotmesh::mesh::split_cells(mesh, split));
    std::printf("wrote ramp2d.msh, ramp2d-triangles.msh, ramp2d-hybrid.msh and ramp.csv in %s\n", folder.c_str());
  });
}
