// hotmesh sample: a straight rectangular duct whose floor is a bicubic B-spline surface (not a
// surface of revolution, not a plane), bulged and sheared by an FEM deflection field: walls on
// CAD faces of any shape (issue 23), the deflected floor known exactly.
//
// What it shows: a 3D wall that hotmesh moves through the CAD face it lies on and an FEM table
// of x, y, z nodes, with no axis: the FEM nodes projected onto the floor face give their (t, s),
// a deflection field d(t, s) is fitted over the face, and the floor patch is moved onto
// S + d (duct-prescribed.yaml) or its nodes slide over it (duct-sliding.yaml); then a second
// load restarts from the sliding run (duct-restart.yaml). duct_wall_distance measures how far
// the moved floor is from the exact deflected floor. README.md is the recipe.
//
// Run:   build/samples/duct3d/make_duct3d [--cells NX,NY,NZ] [OUTPUT_FOLDER]
// (default 48,16,12 cells and the current folder). Writes, in millimetres:
//   duct.step, duct.iges   the six faces: 1 floor (B-spline), 2 ceiling, 3 side_right (y = 0),
//                          4 side_left (y = 2h), 5 inlet (x = 0), 6 outlet (x = 4h)
//   duct.msh               the hex mesh (Gmsh 4.1, ASCII), patches named and tagged as the faces
//   floor.csv              the FEM table of load hot1 on 23 x 10 scattered floor nodes
//   floor_grid.csv         the same load on the 23 x 10 grid of nodes, for comparison
//   floor_hot2.csv         load hot2 on the scattered nodes: the next coupling iteration
// and prints the sizes, the mesh quality and the loads. The committed files in samples/duct3d/
// are this program's default output.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "duct_floor.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/validate.hpp"

namespace {

using namespace hotmesh::samples::duct3d;

struct Options {
  MeshSize size;
  std::filesystem::path folder = ".";
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (a == "--cells") {
      if (i + 1 >= argc) throw std::invalid_argument("--cells needs NX,NY,NZ");
      auto& s = o.size;
      if (std::sscanf(argv[++i], "%d,%d,%d", &s.cells_x, &s.cells_y, &s.cells_z) != 3 || s.cells_x < 1 ||
          s.cells_y < 1 || s.cells_z < 1) {
        throw std::invalid_argument("--cells needs three positive counts NX,NY,NZ");
      }
    } else if (a == "-h" || a == "--help") {
      std::printf("usage: make_duct3d [--cells NX,NY,NZ] [FOLDER]\n");
      std::exit(0);
    } else if (!a.empty() && a[0] == '-') {
      throw std::invalid_argument("unknown option " + std::string(a));
    } else {
      o.folder = a;
    }
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    std::filesystem::create_directories(o.folder);

    // 1. The CAD model: the floor surface and the five planes around it.
    const auto cad = cad_model();
    hotmesh::io::write_file_atomically(o.folder / kCadFile, hotmesh::geometry::to_step(cad));
    hotmesh::io::write_file_atomically(o.folder / kIgesFile, hotmesh::geometry::to_iges(cad));

    // 2. The mesh: floor nodes on the floor surface, straight vertical lines up to the ceiling.
    const auto floor = floor_surface();
    auto mesh = duct_mesh(floor, o.size);
    hotmesh::mesh::validate_mesh(mesh);
    const auto quality = hotmesh::mesh::summarize_quality(hotmesh::mesh::scaled_jacobians(mesh.cells, mesh.points));
    hotmesh::io::write_gmsh(o.folder / kMeshFile, mesh);

    // 3. The FEM tables of the two loads.
    const DeflectedFloor hot1(floor, kHot1), hot2(floor, kHot2);
    hotmesh::io::write_file_atomically(o.folder / "floor.csv", fem_table_csv(hot1, FemLayout::scattered));
    hotmesh::io::write_file_atomically(o.folder / "floor_grid.csv", fem_table_csv(hot1, FemLayout::grid));
    hotmesh::io::write_file_atomically(o.folder / "floor_hot2.csv", fem_table_csv(hot2, FemLayout::scattered));

    // 4. Summary.
    std::string out = fmt::format("# duct3d\n\nWritten to {}: {}, {}, {}, floor.csv, floor_grid.csv, floor_hot2.csv.\n\n",
                                  o.folder.string(), kCadFile, kIgesFile, kMeshFile);
    out += fmt::format("Duct {} x {} x {} mm (4h x 2h x h, h = {} mm); floor: bicubic B-spline, {} x {} poles.\n\n",
                       kLength, kWidth, kCeiling, kH, floor.u_count(), floor.v_count());
    out += "| cells | nodes | min scaled Jacobian | mean | inverted |\n|---|---|---|---|---|\n";
    out += fmt::format("| {} ({} x {} x {}) | {} | {:.3f} | {:.3f} | {} |\n\n", mesh.cell_count(), o.size.cells_x,
                       o.size.cells_y, o.size.cells_z, mesh.node_count(), quality.min_scaled_jacobian,
                       quality.mean_scaled_jacobian, quality.inverted_cells);
    out += "| patch (tag = CAD face) | faces |\n|---|---|\n";
    for (const auto& p : mesh.patches) out += fmt::format("| {} ({}) | {} |\n", p.name, p.tag, p.faces.size());
    out += fmt::format("\nFEM tables: {} x {} nodes on face {} (floor).\n", kFemNodesX, kFemNodesY, kFloorFace);
    for (const Load* l : {&kHot1, &kHot2}) {
      out += fmt::format("  {}: bulge {:g} mm at (x, y) = ({:g}, {:g}) mm, shear {:g} mm\n", l->name, l->bulge,
                         l->centre_x * kLength, l->centre_y * kWidth, l->shear);
    }
    std::fputs(out.c_str(), stdout);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_duct3d: %s\n", e.what());
    return 1;
  }
}
