// hotmesh sample duct3d, the hybrid mesh (issue 24): the duct of duct.msh meshed with prism
// layers on the floor (the deforming wall) and tetrahedra in the core, by gmsh.
//
// Gmsh meshes the flat duct [0, 4h] x [0, 2h] x [0, h] (duct-hybrid.geo; its output
// duct-hybrid-flat.msh is committed, so that nothing here needs gmsh). This program lifts every
// node onto the B-spline floor with the map of duct.msh's hexes (duct_floor.cpp, duct_mesh),
//     (x, y, z) -> (x, y, lerp(f(x, y), h, z / h)),   f(x, y) = S(x, y).z,
// along vertical lines: the floor nodes (z = 0) go to (x, y, f(x, y)), on the CAD floor to
// rounding; the ceiling nodes (z = h) stay exactly on z = h; x and y do not change, so the side,
// inlet and outlet nodes stay exactly on their planes. Gmsh never sees the exact floor. The
// cells are validated (reversed cells renumbered) and written, patches named and tagged as the
// CAD faces of duct.step (floor = 1, ..., outlet = 6; the physical groups of the .geo).
//
// Run:   build/samples/duct3d/make_duct_hybrid [--flat FLAT.msh]... [OUTPUT_FOLDER]
// (default: the committed duct-hybrid-flat.msh and duct-hybrid-mixed-flat.msh, and the current
// folder). Writes each FLAT.msh lifted as its name without "-flat" (duct-hybrid.msh,
// duct-hybrid-mixed.msh) and prints its cells by type, quality and patches. The committed
// samples/duct3d/duct-hybrid*.msh are this program's default output. To change a mesh, edit
// its .geo and rerun (in samples/duct3d/)
//     gmsh -3 -format msh41 -o duct-hybrid-flat.msh duct-hybrid.geo
//     gmsh -3 -format msh41 -o duct-hybrid-mixed-flat.msh duct-hybrid-mixed.geo
// duct-hybrid: prism layers and tetrahedra; duct-hybrid-mixed: prism layers upstream, hexahedron
// layers downstream, pyramids on them, tetrahedra (every 3D cell type).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "duct_floor.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/mesh/element.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/validate.hpp"

#ifndef HOTMESH_DUCT3D_SOURCE_DIR
#define HOTMESH_DUCT3D_SOURCE_DIR "."
#endif

namespace {

using namespace hotmesh::samples::duct3d;

struct Options {
  std::vector<std::filesystem::path> flat;
  std::filesystem::path folder = ".";
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (a == "--flat") {
      if (i + 1 >= argc) throw std::invalid_argument("--flat needs a file");
      o.flat.emplace_back(argv[++i]);
    } else if (a == "-h" || a == "--help") {
      std::printf("usage: make_duct_hybrid [--flat FLAT.msh]... [FOLDER]\n");
      std::exit(0);
    } else if (!a.empty() && a[0] == '-') {
      throw std::invalid_argument("unknown option " + std::string(a));
    } else {
      o.folder = a;
    }
  }
  if (o.flat.empty()) {
    for (const char* name : {"duct-hybrid-flat.msh", "duct-hybrid-mixed-flat.msh"}) {
      o.flat.push_back(std::filesystem::path(HOTMESH_DUCT3D_SOURCE_DIR) / name);
    }
  }
  return o;
}

/// FLAT.msh's output name: without "-flat" ("duct-hybrid-flat.msh" -> "duct-hybrid.msh").
std::string lifted_name(const std::filesystem::path& flat) {
  std::string stem = flat.stem().string();
  const std::string suffix = "-flat";
  if (stem.size() > suffix.size() && stem.ends_with(suffix)) stem.resize(stem.size() - suffix.size());
  else stem += "-lifted";
  return stem + ".msh";
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    std::filesystem::create_directories(o.folder);

    for (const auto& flat : o.flat) {
      auto mesh = hotmesh::io::read_gmsh(flat);
      if (mesh.dimension != 3) throw std::invalid_argument(flat.string() + " is not a 3D mesh");
      for (std::size_t i = 0; i < kPatchNames.size(); ++i) {
        const auto* p = mesh.find_patch(kPatchNames[i]);
        if (!p || p->tag != static_cast<int>(i) + 1) {
          throw std::invalid_argument(fmt::format("{} has no patch '{}' tagged {} (the CAD face)", flat.string(),
                                                  kPatchNames[i], i + 1));
        }
      }
      // Lift the flat duct onto the floor (duct_mesh's map, with w = z / h).
      const auto floor = floor_surface();
      for (auto& p : mesh.points) {
        if (p.z < 0.0 || p.z > kCeiling) {
          throw std::invalid_argument(fmt::format("a node at z = {} is outside the flat duct", p.z));
        }
        p = {p.x, p.y, std::lerp(floor.point(p.x, p.y).z, kCeiling, p.z / kCeiling)};
      }
      const auto report = hotmesh::mesh::validate_mesh(mesh);
      const auto jacobians = hotmesh::mesh::scaled_jacobians(mesh.cells, mesh.points);
      const auto quality = hotmesh::mesh::summarize_quality(jacobians);
      const auto file = o.folder / lifted_name(flat);
      hotmesh::io::write_gmsh(file, mesh);

      // Per cell type: count, worst scaled Jacobian.
      std::map<hotmesh::mesh::ElementType, std::pair<std::size_t, double>> by_type;
      for (std::size_t c = 0; c < mesh.cells.size(); ++c) {
        auto [it, added] = by_type.try_emplace(mesh.cells.type(c), 0, 1.0);
        ++it->second.first;
        it->second.second = std::min(it->second.second, jacobians[c]);
      }
      std::string out = fmt::format("# {}\n\nRead {}, lifted onto the floor, written to {} ({} cells renumbered).\n\n",
                                    lifted_name(flat), flat.string(), file.string(), report.reoriented_cells);
      out += fmt::format("{} cells, {} nodes; min scaled Jacobian {:.3f}, mean {:.3f}, inverted {}.\n\n",
                         mesh.cell_count(), mesh.node_count(), quality.min_scaled_jacobian, quality.mean_scaled_jacobian,
                         quality.inverted_cells);
      out += "| cell type | cells | min scaled Jacobian |\n|---|---|---|\n";
      for (const auto& [type, v] : by_type) {
        out += fmt::format("| {} | {} | {:.3f} |\n", hotmesh::mesh::name(type), v.first, v.second);
      }
      out += "\n| patch (tag = CAD face) | faces |\n|---|---|\n";
      for (const auto& p : mesh.patches) out += fmt::format("| {} ({}) | {} |\n", p.name, p.tag, p.faces.size());
      std::fputs(out.c_str(), stdout);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_duct_hybrid: %s\n", e.what());
    return 1;
  }
}
