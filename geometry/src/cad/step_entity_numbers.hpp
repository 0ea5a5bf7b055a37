// hotmesh geometry (internal): a STEP file whose entity instances repeat a number is refused
// before OpenCASCADE parses it. OpenCASCADE 7.6 reads uninitialised memory on such a file
// (StepData_StepReaderData::SetEntityNumbers) and may spin there for ever: the fuzz target of
// the STEP reader hung on three of them (docs/fuzzing.md).
#pragma once

#include <filesystem>

namespace hotmesh::geometry::detail {

/// One pass over the file's statements (ISO 10303-21: strings and comments skipped); throws
/// hotmesh::InputError naming the file, the line of the second definition and the first, if
/// an instance number `#N =` is defined twice.
void refuse_repeated_entity_numbers(const std::filesystem::path& path);

}  // namespace hotmesh::geometry::detail
