// hotmesh io: nothing the user gave us is ever lost. Outputs go to a folder of their own;
// a folder that holds inputs is refused unless forced, and no output may replace an input.
#pragma once

#include <filesystem>
#include <span>

namespace hotmesh::io {

/// Creates `folder` (with parents) for a run's outputs. Throws hotmesh::InputError if it is
/// not a folder, cannot be created, or holds one of `inputs` (directly or below) and `force`
/// is false.
void prepare_output_folder(const std::filesystem::path& folder, std::span<const std::filesystem::path> inputs,
                           bool force);

/// Throws hotmesh::InputError if writing `output` would replace one of `inputs`.
void refuse_overwriting_input(const std::filesystem::path& output, std::span<const std::filesystem::path> inputs);

}  // namespace hotmesh::io
