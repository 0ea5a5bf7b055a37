// hotmesh api: what `hotmesh deform` writes to its output folder: deformed.msh and
// deformed.vtu (the final mesh, or the last valid one), failed.vtu when the motion failed,
// PNG pictures for 2D meshes, and report.json.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "hotmesh/deform/mesh_motion.hpp"
#include "hotmesh/io/case_file.hpp"
#include "hotmesh/setup/case_setup.hpp"
#include "hotmesh/io/checkpoint_file.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "hotmesh/parallel/threads.hpp"

namespace hotmesh::api {

struct RunTimings {
  double read = 0.0;    ///< case, mesh and tables, with validation
  double shapes = 0.0;  ///< deflected shapes
  double write = 0.0;   ///< outputs
  double wall = 0.0;    ///< the whole run (this process: a resumed run's own time)
  int checkpoints = 0;  ///< checkpoints written
  double checkpoint = 0.0;  ///< writing them
  std::uint64_t checkpoint_bytes = 0;  ///< size of the last one
  std::uint64_t peak_memory_all_ranks = 0;  ///< every process's peak resident memory, summed
};

/// The threads of a run: what they were chosen from, since when the load is measured, the
/// choice and how waiting threads wait (hotmesh/parallel/threads.hpp).
struct RunThreads {
  parallel::ThreadInputs inputs;
  parallel::LoadProbe load;  ///< from the start of the run
  parallel::ThreadChoice choice;
  std::string wait;
};

struct RunOutputs {
  std::vector<std::filesystem::path> files;
};

/// The names of every file a run may write (to check none would replace an input), relative
/// to the output folder.
std::vector<std::string> output_names(const io::Case& c, const io::LoadedMesh& loaded);

/// What a failed run ran into, in words: "Newton did not converge; no cell inverted", ...
std::string failure_text(const deform::MotionFailure& failure);

/// deformed.msh, deformed.vtu, the pictures and, for a mesh read from another solver's format,
/// the mesh written back in it (`write_back`). `solver`: the flow solver's measures of the
/// result's mesh.
RunOutputs write_outputs(const std::filesystem::path& folder, const io::Case& c, const io::LoadedMesh& loaded,
                         const setup::CaseSetup& setup, const deform::MotionResult& result,
                         const mesh::SolverQuality& solver, bool binary_msh, const io::WriteBackOptions& write_back);

/// The text of report.json (see write_report) listing `outputs` as the files written.
std::string deform_report(const std::filesystem::path& folder, const io::Case& c, const io::LoadedMesh& loaded,
                          const setup::CaseSetup& setup, const deform::MotionResult& result,
                          const mesh::SolverQuality& solver, const RunTimings& timings, const RunThreads& threads,
                          const RunOutputs& outputs, const io::CheckpointInfo* resumed = nullptr);

/// report.json: status, increments with Newton and PCG iterations, quality, times per phase;
/// for a resumed run (`resumed`: the checkpoint it continued from) every increment, those of
/// the interrupted run included.
void write_report(const std::filesystem::path& folder, const io::Case& c, const io::LoadedMesh& loaded,
                  const setup::CaseSetup& setup, const deform::MotionResult& result, const mesh::SolverQuality& solver,
                  const RunTimings& timings, const RunThreads& threads, RunOutputs& outputs,
                  const io::CheckpointInfo* resumed = nullptr);

/// The linear solver a run of case `c` on `mesh` with `setup` uses, and why: the case file's, or
/// what `linear: auto` picks for the mesh, its sliding walls and the processes
/// (deform::choose_linear_solver).
deform::LinearSolverChoice linear_solver_of(const io::Case& c, const mesh::Mesh& mesh, const setup::CaseSetup& setup);

/// The process's peak resident memory (VmHWM), or 0 where /proc does not tell.
std::uint64_t peak_memory_bytes();

}  // namespace hotmesh::api
