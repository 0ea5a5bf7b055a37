// hotmesh benchmark: what the checkpoints of a long `hotmesh deform` run cost. A hex block of
// about --cells cells (default 2.7 million, the size of a large stator-well sector) stands for
// the mesh; its six sides are taken as sliding walls (their nodes carry targets and hints). For
// each run it times, as the command does them:
//   - state: building the deform::MotionCheckpoint from the solver (a copy of every point, now
//            and at the start of the increment),
//   - write: io::write_checkpoint (temporary file, fsync, rename) into --dir,
//   - read:  io::read_checkpoint, with its checks, as `--resume` does,
//   - hash:  io::input_fingerprints of the case's inputs (the mesh file, binary Gmsh 4.1) and
//            the mesh's fingerprint (io::checkpoint_origin), done once per run.
// Prints a Markdown table of medians over --runs. Results in docs/performance.md.
//
//   ninja -C build bench_checkpoint && build/bench/bench_checkpoint [--cells 2700000] [--runs 3] [--dir DIR]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "hotmesh/deform/mesh_motion.hpp"
#include "hotmesh/mesh/structured_mesh.hpp"
#include "hotmesh/io/checkpoint_file.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "machine_load.hpp"
#include "timing.hpp"

using namespace hotmesh;

namespace {

using bench::Clock;
using bench::seconds_since;
using bench::median;

/// The state a run hands out after an accepted increment: every point, those at the start of
/// the increment (the predictor's), and each boundary node as a sliding node with a target and
/// hints; 8 increments of records.
deform::MotionCheckpoint state_of(const mesh::Mesh& mesh) {
  deform::MotionCheckpoint s;
  s.increments = 16;
  s.finished_increments = 8;
  s.lambda = 0.5;
  s.points = mesh.points;
  s.previous_points = mesh.points;
  s.previous_lambda = 0.4375;
  std::vector<char> boundary(mesh.node_count(), 0);
  for (const auto& patch : mesh.patches) {
    for (mesh::NodeId n : patch.nodes) boundary[static_cast<std::size_t>(n)] = 1;
  }
  for (std::size_t n = 0; n < mesh.node_count(); ++n) {
    if (boundary[n]) s.sliding.push_back({static_cast<mesh::NodeId>(n), mesh.points[n], {{{.t = 0.5}, {.t = 0.25}, {.t = 0.0}}}});
  }
  for (int k = 1; k <= 8; ++k) {
    deform::IncrementRecord r;
    r.increment = k;
    r.accepted = r.converged = true;
    for (int i = 0; i < 12; ++i) r.newton.push_back({1.0 / (i + 1), 400, true, 1e-3, 1e-9});
    s.records.push_back(r);
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  long cells = 2'700'000;
  int runs = 3;
  std::filesystem::path dir = std::filesystem::temp_directory_path() / "hotmesh-bench-checkpoint";
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (a == "--cells" && i + 1 < argc) {
      cells = std::atol(argv[++i]);
    } else if (a == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--dir" && i + 1 < argc) {
      dir = argv[++i];
    } else {
      std::fprintf(stderr, "usage: bench_checkpoint [--cells N] [--runs R] [--dir DIR]\n");
      return 2;
    }
  }
  try {
    const int n = std::max(2, static_cast<int>(std::lround(std::cbrt(static_cast<double>(cells)))));
    const auto line = mesh::uniform_line(0.0, 1.0, n);
    const mesh::Mesh mesh = mesh::structured_hexes(line, line, line);
    std::filesystem::create_directories(dir);
    io::Case c;
    c.file = dir / "case.yaml";
    c.mesh = dir / "block.msh";
    io::write_gmsh(c.mesh, mesh, {.binary = true});
    {
      std::FILE* f = std::fopen(c.file.c_str(), "w");
      if (!f) throw std::runtime_error("cannot write " + c.file.string());
      std::fputs("mesh: block.msh\n", f);
      std::fclose(f);
    }
    const auto path = dir / io::kCheckpointName;

    std::vector<double> state, write, read, hash, others;
    std::uintmax_t bytes = 0;
    std::size_t sliding = 0;
    for (int r = 0; r < runs; ++r) {
      const bench::LoadProbe load;
      auto t = Clock::now();
      const auto inputs = io::input_fingerprints(c);
      const io::CheckpointOrigin origin = io::checkpoint_origin(c, mesh, inputs);
      hash.push_back(seconds_since(t));
      t = Clock::now();
      deform::MotionCheckpoint s = state_of(mesh);
      state.push_back(seconds_since(t));
      sliding = s.sliding.size();
      t = Clock::now();
      io::write_checkpoint(path, origin, s);
      write.push_back(seconds_since(t));
      bytes = std::filesystem::file_size(path);
      t = Clock::now();
      const io::Checkpoint k = io::read_checkpoint(path, mesh, inputs);
      read.push_back(seconds_since(t));
      if (k.state.points.size() != mesh.node_count()) throw std::runtime_error("read back a different checkpoint");
      others.push_back(load.others());
    }
    const auto mesh_bytes = std::filesystem::file_size(c.mesh);
    std::printf("%s", fmt::format("hex block of {} cells, {} nodes, {} sliding nodes; checkpoint {:.1f} MB, mesh file "
                                  "{:.1f} MB; in {}; median of {} runs\n\n",
                                  mesh.cell_count(), mesh.node_count(), sliding, static_cast<double>(bytes) / 1e6,
                                  static_cast<double>(mesh_bytes) / 1e6, dir.string(), runs)
                          .c_str());
    std::printf("| state copy (s) | write + fsync (s) | read + checks (s) | input hashes (s) | other load (cores) |\n");
    std::printf("|---:|---:|---:|---:|---:|\n");
    std::printf("%s", fmt::format("| {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.2f} |\n", median(state), median(write),
                                  median(read), median(hash), median(others))
                          .c_str());
    std::filesystem::remove_all(dir);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_checkpoint: %s\n", e.what());
    return 1;
  }
  return 0;
}
