// hotmesh api: one run of `hotmesh deform`, in the steps that the command and the library
// (<hotmesh/hotmesh.hpp>) share: the case's CAD and mesh read and checked with the threads
// chosen (1), the deflected shapes (2), the motion with its progress logged (3) and the
// outputs with report.json and restart.hmr (4). What only the command does (its options, the
// output folder's checks, checkpoints and --resume, the job's processes) stays in app/cli.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "hotmesh/api/deform_checkpoint.hpp"
#include "hotmesh/api/deform_outputs.hpp"
#include "hotmesh/core/clock.hpp"
#include "hotmesh/deform/mesh_motion.hpp"
#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/io/case_file.hpp"
#include "hotmesh/io/checkpoint_file.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "hotmesh/io/restart_file.hpp"
#include "hotmesh/parallel/threads.hpp"
#include "hotmesh/setup/case_setup.hpp"

namespace hotmesh::api {

/// Where a run is, for the message if memory runs out (kept outside the run, which the
/// exception unwinds).
struct RunState {
  std::string phase = "reading the case";
  std::size_t nodes = 0;
  std::size_t cells = 0;
  std::filesystem::path checkpoint;  ///< set once the motion starts
  int checkpoint_increments = -1;    ///< increments done in the last checkpoint written, -1: none
};

/// A case with the files it names read and checked together, and the threads it runs on.
struct LoadedCase {
  io::Case c;
  std::optional<geometry::CadModel> cad;
  io::LoadedMesh loaded;
  RunThreads threads;
};

/// The threads the user asked for: `threads` (> 0; 0 lets hotmesh choose, < 0: not given),
/// else the case's solver.threads, else OMP_NUM_THREADS; none (0) lets hotmesh choose.
/// `option` names where `threads` came from in the reason ("--threads").
parallel::ThreadRequest thread_request(int threads, const char* option, const io::Case& c);

/// 1. Reads the CAD file and the mesh of `in.c`, checks the case against the mesh and starts
/// the threads (`request`) the mesh's size calls for; `in.threads.wait` (how waiting threads
/// wait: the program's business) is logged with them. Throws hotmesh::InputError.
void load_case(LoadedCase& in, const parallel::ThreadRequest& request, RunState& state);

/// 2. The deflected shapes from the FEM tables (section 4.2), rebased on `previous` for a
/// restarted run (section 4.3), logged per patch.
setup::CaseSetup set_up_shapes(const LoadedCase& in, const io::RestartState* previous);

/// How the motion runs and who hears of it.
struct MotionSettings {
  bool progress = false;  ///< log every Newton step at info level (as for large meshes)
  const deform::MotionStart* restart = nullptr;  ///< a restarted run's start (section 4.3)
  const io::Checkpoint* resumed = nullptr;       ///< an interrupted run's checkpoint (--resume)
  std::filesystem::path checkpoint_path;         ///< where checkpoints go, for the log
  std::function<void(const deform::MotionCheckpoint&)> checkpoint;
  std::function<void(const deform::NewtonProgress&)> newton;        ///< after the log line
  std::function<void(const deform::IncrementRecord&)> increment;    ///< after the log line
};

/// 3. The motion, increment by increment, logged. A free rigid motion of the patches as a
/// whole is the case's mistake: hotmesh::InputError naming its `patches:` line.
deform::MotionResult move_the_mesh(const LoadedCase& in, const setup::CaseSetup& setup, const MotionSettings& settings,
                                   RunState& state, Clock::time_point start);

/// Logs what the motion found and did besides moving: how far each wall was from its
/// undeformed wall, the corners held, notes, the corner pass's repair, the motion's times.
void log_motion(const mesh::Mesh& mesh, const deform::MotionResult& result);

/// How a run's outputs are written.
struct OutputSettings {
  bool binary_msh = false;
  io::WriteBackOptions write_back;
  CheckpointWriter* checkpoints = nullptr;         ///< removed once the outputs are written
  const io::CheckpointInfo* resumed_from = nullptr;
};

/// 4. The outputs in `folder` (deformed mesh, VTU, pictures, the mesh written back in its own
/// format, restart.hmr on success, report.json), each written atomically, for the run of case
/// `c` (`in` as loaded; `c` is `in.c` unless its deflections changed since); logs the outcome.
/// The exit code: 0 done, 1 the motion failed (the last valid mesh written).
int write_run_outputs(const std::filesystem::path& folder, const io::Case& c, const LoadedCase& in,
                      const setup::CaseSetup& setup, const deform::MotionResult& result,
                      const OutputSettings& settings, RunTimings& timings, Clock::time_point start);

}  // namespace hotmesh::api
