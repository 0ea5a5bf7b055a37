// hotmesh sample: the turbine stator well of the paper's section 6 (Amirante, Hills & Barnes,
// Figs. 11-17): a 3.6 degree sector of the interstage cavity of a HP turbine, with a labyrinth
// seal of three fins hanging from the stator's land over the rotor's disc base, cavities up- and
// downstream opening to the main annulus through rim gaps, and the upstream disc made of an
// upper and a lower component joined by a 1 mm radial gap.
//
// Run:   build/samples/stator_well/make_stator_well [--cells N | --refinement S] [--label NAME]
//                                                   [--ascii | --binary] [--engine-formats] [OUTPUT_FOLDER]
// (default: 18 000 cells, label "small", the current folder). Writes
//   stator_well.step    the meridional profile revolved by 3.6 degrees about z, one face per
//                       curve, numbered by patch (README.md lists them)
//   stator_well.msh     the hex mesh of the sector (Gmsh 4.1, binary unless --ascii)
//   <patch>.csv         one FEM deflection table per metal patch (r, z, dr, dz), severe case
//   case_<label>.yaml, case_<label>_nosliding.yaml    the case files, sliding on and off
//   case_<label>_cgns.yaml, case_<label>_foam.yaml    the sliding case on the meshes below
// and with --engine-formats also
//   stator_well.cgns    the sector as structured multi-block CGNS (one zone per block, 1-to-1
//                       connections, BCs named as the patches)
//   stator_well_foam/   the sector as an OpenFOAM case (constant/polyMesh, ASCII unless --binary
//                       is given explicitly; system/ for checkMesh)
// and prints a summary: size, quality, patches with their roles, CAD faces and tables, and what
// the deflections do to the seal clearance and the joint.
// The committed files in samples/stator_well/ are this program's default output.
//
// Sizes: --cells N picks the refinement whose cell count is nearest N; 18 000 (the committed
// files and the tests), 200 000 and 2 700 000 (the paper's mesh) are the documented ones.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "fem_tables.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/validate.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "stator_well.hpp"

namespace {

using namespace hotmesh::samples::stator_well;

struct Options {
  std::int64_t cells = kSmallCells;
  double refinement = 0.0;  // > 0: use it instead of cells
  std::string label = "small";
  bool binary = true;
  bool binary_given = false;
  bool engine_formats = false;
  std::filesystem::path folder = ".";
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(std::string(a) + " needs a value");
      return argv[++i];
    };
    if (a == "--cells") {
      o.cells = std::stoll(value());
    } else if (a == "--refinement") {
      o.refinement = std::stod(value());
    } else if (a == "--label") {
      o.label = value();
    } else if (a == "--ascii" || a == "--binary") {
      o.binary = a == "--binary";
      o.binary_given = true;
    } else if (a == "--engine-formats") {
      o.engine_formats = true;
    } else if (a == "-h" || a == "--help") {
      std::printf(
          "usage: make_stator_well [--cells N | --refinement S] [--label NAME] [--ascii | --binary] "
          "[--engine-formats] [FOLDER]\n");
      std::exit(0);
    } else if (!a.empty() && a[0] == '-') {
      throw std::invalid_argument("unknown option " + std::string(a));
    } else {
      o.folder = a;
    }
  }
  if (o.cells <= 0 || o.refinement < 0.0) throw std::invalid_argument("--cells and --refinement must be positive");
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    const auto start = std::chrono::steady_clock::now();
    std::filesystem::create_directories(o.folder);

    // 1. The profile and its CAD model.
    const auto loop = profile();
    hotmesh::io::write_file_atomically(o.folder / kCadFile, hotmesh::geometry::to_step(cad_model(loop)));

    // 2. The mesh: blocks of the meridional section, swept in theta.
    const hotmesh::samples::BlockMesher mesher(block_layout(loop), spacing_field());
    const Size size = o.refinement > 0.0 ? size_at(mesher, o.refinement) : size_for_cells(mesher, o.cells);
    const auto section = mesher.mesh(size.refinement);
    auto mesh = sector_mesh(section, loop, size.theta_cells);
    hotmesh::mesh::validate_mesh(mesh);
    const auto quality = hotmesh::mesh::summarize_quality(hotmesh::mesh::scaled_jacobians(mesh.cells, mesh.points));
    hotmesh::io::write_gmsh(o.folder / kMeshFile, mesh, {.binary = o.binary});

    // 3. FEM tables and case files.
    const SevereCase severe;
    const auto tables = fem_tables(loop, severe);
    for (const auto& t : tables) hotmesh::io::write_file_atomically(o.folder / table_file(t.patch), table_csv(t, severe));
    for (const bool sliding : {true, false}) {
      hotmesh::io::write_file_atomically(o.folder / case_file_name(o.label, sliding), case_file(loop, o.label, sliding));
    }

    // 4. The case files on the sector in engine formats, and with --engine-formats the sector as
    //    structured multi-block CGNS and as an OpenFOAM case.
    for (const auto& [format, file] : {std::pair<std::string, std::string>{"cgns", kCgnsFile}, {"foam", kFoamCase}}) {
      hotmesh::io::write_file_atomically(o.folder / engine_case_file_name(o.label, format),
                                         engine_case_file(loop, o.label, format, file));
    }
    if (o.engine_formats) {
      write_sector_cgns(o.folder / kCgnsFile, section, mesh, loop, size.theta_cells);
      write_sector_foam(o.folder / kFoamCase, mesh, o.binary_given && o.binary);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    // 5. Summary.
    std::string out = fmt::format("# stator_well ({})\n\nWritten to {} in {:.1f} s.\n\n", o.label, o.folder.string(), seconds);
    out += fmt::format(
        "| refinement | theta cells | quads (section) | hex cells | nodes | min scaled Jacobian | mean |\n"
        "|---|---|---|---|---|---|---|\n| {:.4f} | {} | {} | {} | {} | {:.3f} | {:.3f} |\n\n",
        size.refinement, size.theta_cells, size.quads, size.cells, mesh.node_count(), quality.min_scaled_jacobian,
        quality.mean_scaled_jacobian);
    out += "| patch | faces (mesh) | role (sliding on / off) | CAD faces | FEM table | FEM nodes |\n|---|---|---|---|---|---|\n";
    for (const auto& p : mesh.patches) {
      const auto patch = static_cast<Patch>(p.tag - 1);
      const auto ids = cad_faces(loop, patch);
      std::string table = "-", nodes = "-";
      for (const auto& t : tables) {
        if (t.patch == patch) {
          table = table_file(patch);
          nodes = std::to_string(t.nodes.size());
        }
      }
      const std::string roles = std::string(role(patch, true)) + " / " + role(patch, false);
      out += fmt::format("| {} | {} | {} | {} | {} | {} |\n", p.name, p.faces.size(), roles,
                         ids.empty() ? "-" : fmt::format("{}", fmt::join(ids, ", ")), table, nodes);
    }
    const GapChanges gaps = gap_changes(tables);
    out += fmt::format(
        "\nSevere case: rotor dz = {:.2f} mm, rotor dr = {:.2f} mm at r = 420 mm (stator {:.2f} mm), lower disc "
        "component dr + {:.2f} mm.\nSeal clearance {:.2f} -> {:.2f} mm ({:.0f} % closed); joint gap B-C {:.2f} -> "
        "{:.2f} mm.\n",
        severe.axial_shift * 1e3, severe.rotor_growth * 1e3, severe.stator_growth * 1e3, severe.joint_jump * 1e3,
        gaps.clearance_before * 1e3, gaps.clearance_after * 1e3, 100.0 * (1.0 - gaps.clearance_after / gaps.clearance_before),
        gaps.joint_before * 1e3, gaps.joint_after * 1e3);
    std::fputs(out.c_str(), stdout);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_stator_well: %s\n", e.what());
    return 1;
  }
}
