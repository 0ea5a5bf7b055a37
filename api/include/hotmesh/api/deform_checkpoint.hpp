// hotmesh api: checkpoints of `hotmesh deform` (io/checkpoint_file.hpp). After every accepted
// increment the run replaces <output>/checkpoint.hmc; `--resume` continues from it. A run that
// ends (done, or failed with exit code 1) removes it; one that is killed or runs out of memory
// leaves it, and a new run into that folder is refused unless it resumes or is forced.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hotmesh/mesh/mesh.hpp"
#include "hotmesh/deform/mesh_motion.hpp"
#include "hotmesh/io/case_file.hpp"
#include "hotmesh/io/checkpoint_file.hpp"

namespace hotmesh::api {

/// Writes the checkpoints of one run.
class CheckpointWriter {
 public:
  CheckpointWriter(std::filesystem::path path, const io::Case& c, const mesh::Mesh& mesh,
                   std::vector<io::InputFingerprint> inputs);

  /// The checkpoint observer of deform::move_mesh.
  void write(const deform::MotionCheckpoint& state);
  /// Removes the checkpoint (the run has ended).
  void remove();

  const std::filesystem::path& path() const { return path_; }
  int written() const { return written_; }
  double seconds() const { return seconds_; }      ///< writing all of them
  std::uint64_t bytes() const { return bytes_; }   ///< of the last one

 private:
  std::filesystem::path path_;
  io::CheckpointOrigin origin_;
  int written_ = 0;
  double seconds_ = 0.0;
  std::uint64_t bytes_ = 0;
};

/// A fresh run must not destroy the checkpoint of an interrupted one: throws hotmesh::InputError
/// if `folder` holds one, unless `force`.
void refuse_to_replace_checkpoint(const std::filesystem::path& folder, bool force);

}  // namespace hotmesh::api
