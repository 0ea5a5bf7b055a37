// hotmesh io: nothing the user gave us is ever lost. Outputs go to a folder of their own;
// a folder that holds inputs is refused unless forced, and no output may replace an input.
#pragma once

#include <filesystem>
#include <span>
#include <vector>

namespace hotmesh::io {

/// The folder a command writes its outputs to, made ready before any work starts. If the
/// command ends without writing anything there (a late error), the folders it created are
/// removed again: a failed run leaves no empty folder behind.
class OutputFolder {
 public:
  OutputFolder() = default;
  OutputFolder(OutputFolder&& other) noexcept;
  OutputFolder& operator=(OutputFolder&& other) noexcept;
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;
  /// Removes the folders this object created that are still empty, deepest first.
  ~OutputFolder();

  const std::filesystem::path& path() const { return folder_; }
  /// Keeps the created folders even if empty (e.g. in the ranks of a job that do not write).
  void keep() { created_.clear(); }

 private:
  friend OutputFolder prepare_output_folder(const std::filesystem::path&, std::span<const std::filesystem::path>, bool);
  std::filesystem::path folder_;
  std::vector<std::filesystem::path> created_;  ///< outermost first
};

/// Creates `folder` (with parents) for a run's outputs and checks that files can be written
/// in it. Throws hotmesh::InputError if it is not a folder, cannot be created or written, or
/// holds one of `inputs` (directly or below) and `force` is false.
[[nodiscard]] OutputFolder prepare_output_folder(const std::filesystem::path& folder,
                                                 std::span<const std::filesystem::path> inputs, bool force);

/// Throws hotmesh::InputError if writing `output` would replace one of `inputs`.
void refuse_overwriting_input(const std::filesystem::path& output, std::span<const std::filesystem::path> inputs);

}  // namespace hotmesh::io
