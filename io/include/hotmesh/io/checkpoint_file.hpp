// hotmesh io: checkpoint files (checkpoint.hmc). A long `hotmesh deform` run saves one in its
// output folder after every accepted increment (or piece of a split one), replacing the last;
// a run that was killed (out of memory, a batch system's time limit, a crash) continues from
// it with `hotmesh deform CASE --resume` and ends with the outputs the uninterrupted run would
// have written. The file holds the solver's state (deform::MotionCheckpoint: positions, the
// sliding nodes' targets and projection hints, the pieces of a split increment left, the
// records of the attempts so far) and what the run was made from: a fingerprint of the mesh
// and a hash of every input file, so that a resume with a changed case is refused.
//
// Layout, like restart.hmr: a magic line, a little-endian u64 length and a JSON header
// (versions, inputs, counts, pieces left, records), then arrays (u64 count, then elements): node
// positions, sliding node ids, their targets and hints, and a hash of these arrays.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "hotmesh/mesh/mesh.hpp"
#include "hotmesh/deform/mesh_motion.hpp"
#include "hotmesh/io/case_file.hpp"

namespace hotmesh::io {

/// The name of the checkpoint in a run's output folder.
inline constexpr std::string_view kCheckpointName = "checkpoint.hmc";

/// One input file as a run saw it.
struct InputFingerprint {
  std::filesystem::path file;
  std::uint64_t bytes = 0;
  std::uint64_t hash = 0;
};

/// Size and hash of every file the case reads (Case::inputs(): the case file, mesh, CAD
/// file, restart file and deflection tables). Throws hotmesh::InputError if one cannot be read.
std::vector<InputFingerprint> input_fingerprints(const Case& c);

/// What a checkpoint tells before its state is read: for messages and progress.
struct CheckpointInfo {
  std::string case_file;
  std::string hotmesh_version;
  std::string written_at;  ///< local time, "2024-05-01 13:45:12"
  int increments = 0;
  int finished_increments = 0;
  double lambda = 0.0;
};

/// What a run was made from: the same in all its checkpoints.
struct CheckpointOrigin {
  std::string case_file;
  std::uint64_t mesh_fingerprint = 0;  ///< of the undeformed mesh (mesh_fingerprint())
  std::vector<InputFingerprint> inputs;
};

/// The origin of run `c` on `mesh` (`inputs` from input_fingerprints(c)); computed once a run.
CheckpointOrigin checkpoint_origin(const Case& c, const mesh::Mesh& mesh, std::vector<InputFingerprint> inputs);

struct Checkpoint {
  CheckpointInfo info;
  CheckpointOrigin origin;
  deform::MotionCheckpoint state;
};

/// Writes the state of a run atomically (a crash while writing leaves the previous checkpoint),
/// stamped with this hotmesh's version and the time.
void write_checkpoint(const std::filesystem::path& path, const CheckpointOrigin& origin,
                      const deform::MotionCheckpoint& state);

/// Reads only the header. Throws hotmesh::InputError naming the file if it is not a
/// checkpoint of this format version, or is damaged.
CheckpointInfo read_checkpoint_info(const std::filesystem::path& path);

/// Reads a checkpoint and checks that it belongs to this run: written by this format, for
/// this mesh, from the same input files byte for byte. Throws hotmesh::InputError naming the
/// checkpoint and what differs (the file that changed) otherwise.
Checkpoint read_checkpoint(const std::filesystem::path& path, const mesh::Mesh& mesh,
                           std::span<const InputFingerprint> inputs);

}  // namespace hotmesh::io
