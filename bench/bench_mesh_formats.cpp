// hotmesh benchmark: reading and writing back the stator-well sector (samples/stator_well) in
// each mesh format hotmesh reads: binary Gmsh .msh, structured multi-block CGNS (one zone per
// block, as make_stator_well --engine-formats writes it) and a binary OpenFOAM polyMesh. The
// sector is generated once (default: the paper's 2.7 million cells) and written in the three
// formats to a temporary folder; then, several times each, the format's reader alone,
// read_mesh (the reader and the validation every read does) and the write-back of the mesh read (deformed.cgns, the polyMesh
// folder; for Gmsh, write_gmsh binary as deformed.msh is written). Prints a Markdown table of
// the medians for docs/performance.md.
//
// Run:   ninja -C build bench_mesh_formats && build/bench/bench_mesh_formats [CELLS [REPETITIONS]]
// (default 2700000 5).
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "hotmesh/io/cgns.hpp"
#include "hotmesh/io/foam.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "stator_well.hpp"
#include "timing.hpp"

namespace {

namespace fs = std::filesystem;
using namespace hotmesh;
using namespace hotmesh::samples::stator_well;

/// The median wall-clock time of `repetitions` calls of `work`.
double median_seconds(int repetitions, const std::function<void()>& work) {
  std::vector<double> times;
  for (int r = 0; r < repetitions; ++r) {
    const auto start = bench::Clock::now();
    work();
    times.push_back(bench::seconds_since(start));
  }
  return bench::median(times);
}

std::uintmax_t bytes_in(const fs::path& path) {
  if (!fs::is_directory(path)) return fs::file_size(path);
  std::uintmax_t total = 0;
  for (const auto& e : fs::recursive_directory_iterator(path)) {
    if (e.is_regular_file()) total += e.file_size();
  }
  return total;
}

/// The format's reader alone, without the validation read_mesh adds.
void parse_only(const fs::path& input) {
  switch (io::mesh_format(input)) {
    case io::MeshFormat::gmsh: io::read_gmsh(input); return;
    case io::MeshFormat::cgns: io::read_cgns(input); return;
    case io::MeshFormat::foam: io::read_foam(input); return;
    case io::MeshFormat::vtu: return;
  }
}

struct ReadTimes {
  double parse = 0.0, read = 0.0;
};

/// Prints the format's row; returns its median read times. `msh` zero: this is the .msh file.
ReadTimes time_format(const char* label, const fs::path& input, const fs::path& out, int repetitions, ReadTimes msh) {
  const double parse = median_seconds(repetitions, [&] { parse_only(input); });
  const double read = median_seconds(repetitions, [&] { io::read_mesh(input); });
  const io::LoadedMesh loaded = io::read_mesh(input);
  double write = 0.0;
  if (loaded.write_back) {
    write = median_seconds(repetitions, [&] { loaded.write_back->write(out, loaded.mesh.points, {}); });
  } else {
    write = median_seconds(repetitions, [&] { io::write_gmsh(out / "deformed.msh", loaded.mesh, {.binary = true}); });
  }
  if (msh.read == 0.0) msh = {parse, read};
  std::printf("| %s | %.0f | %.2f | %.2f | %.2f | %.2f | %.2f |\n", label, static_cast<double>(bytes_in(input)) / 1e6,
              parse, parse / msh.parse, read, read / msh.read, write);
  std::fflush(stdout);
  return {parse, read};
}

}  // namespace

int main(int argc, char** argv) {
  const std::int64_t cells = argc > 1 ? std::atoll(argv[1]) : 2700000;
  const int repetitions = argc > 2 ? std::atoi(argv[2]) : 5;
  const fs::path folder = fs::temp_directory_path() / ("hotmesh-bench-formats-" + std::to_string(::getpid()));
  fs::create_directories(folder / "out");

  const auto loop = profile();
  const samples::BlockMesher mesher(block_layout(loop), spacing_field());
  const Size size = size_for_cells(mesher, cells);
  const auto section = mesher.mesh(size.refinement);
  {
    const mesh::Mesh sector = sector_mesh(section, loop, size.theta_cells);
    io::write_gmsh(folder / "sector.msh", sector, {.binary = true});
    write_sector_cgns(folder / "sector.cgns", section, sector, loop, size.theta_cells);
    io::write_foam(folder / "foam", sector, sector.points, {.binary = true});
    std::printf("%lld hex cells, %zu nodes, %zu CGNS zones; median of %d runs\n\n", static_cast<long long>(size.cells),
                sector.node_count(), section.blocks.size(), repetitions);
  }
  std::printf("| format | size (MB) | reader (s) | / .msh | read_mesh: reader + validation (s) | / .msh | write back (s) |\n"
              "|---|---|---|---|---|---|---|\n");
  std::fflush(stdout);
  const ReadTimes msh = time_format("Gmsh 4.1 binary .msh", folder / "sector.msh", folder / "out", repetitions, {});
  time_format("CGNS structured multi-block (HDF5)", folder / "sector.cgns", folder / "out", repetitions, msh);
  time_format("OpenFOAM polyMesh binary", folder / "foam" / "constant" / "polyMesh", folder / "out", repetitions, msh);
  fs::remove_all(folder);
  return 0;
}
