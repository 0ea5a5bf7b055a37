// hotmesh api: the checkpoints of `hotmesh deform` (see deform_checkpoint.hpp).
#include "hotmesh/api/deform_checkpoint.hpp"

#include <chrono>
#include <system_error>

#include <spdlog/spdlog.h>

#include "hotmesh/core/input_error.hpp"

namespace hotmesh::api {

CheckpointWriter::CheckpointWriter(std::filesystem::path path, const io::Case& c, const mesh::Mesh& mesh,
                                   std::vector<io::InputFingerprint> inputs)
    : path_(std::move(path)), origin_(io::checkpoint_origin(c, mesh, std::move(inputs))) {}

void CheckpointWriter::write(const deform::MotionCheckpoint& state) {
  const auto start = std::chrono::steady_clock::now();
  io::write_checkpoint(path_, origin_, state);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::error_code ec;
  bytes_ = std::filesystem::file_size(path_, ec);
  seconds_ += seconds;
  ++written_;
  spdlog::debug("checkpoint at stage {:.4f} ({} of {} increments done): {:.1f} MB written in {:.2f} s", state.lambda,
                state.finished_increments, state.increments, static_cast<double>(bytes_) / 1e6, seconds);
}

void CheckpointWriter::remove() {
  std::error_code ec;
  std::filesystem::remove(path_, ec);
  if (ec) spdlog::warn("could not remove {}: {}", path_.string(), ec.message());
}

void refuse_to_replace_checkpoint(const std::filesystem::path& folder, bool force) {
  const auto path = folder / io::kCheckpointName;
  std::error_code ec;
  if (force || !std::filesystem::exists(path, ec)) return;
  std::string what = "an interrupted run";
  try {
    const io::CheckpointInfo info = io::read_checkpoint_info(path);
    what = fmt::format("an interrupted run of {} ({} of {} increments done, written {})", info.case_file,
                       info.finished_increments, info.increments, info.written_at);
  } catch (const InputError&) {  // damaged: still refuse, it may be all that is left of a long run
  }
  throw InputError::in(folder.string(), fmt::format("the output folder holds {}, the checkpoint of {}: pass --resume "
                                                    "to continue that run, or --force to start again and replace it",
                                                    io::kCheckpointName, what));
}

}  // namespace hotmesh::api
