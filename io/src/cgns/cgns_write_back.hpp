// hotmesh io (private): the moved mesh written back into a copy of the CGNS file it came from.
#pragma once

#include <filesystem>
#include <memory>
#include <vector>

#include "cgns/cgns_reader.hpp"
#include "hotmesh/io/mesh_files.hpp"

namespace hotmesh::io::cgns {

/// deformed.cgns: the input file copied (to a temporary name, renamed when complete) with the
/// grid coordinates of every zone of the base replaced, in their own names and data types.
std::shared_ptr<const MeshWriteBack> make_write_back(const std::filesystem::path& input, const RawMesh& raw,
                                                     std::vector<NodeId> global_of_raw);

}  // namespace hotmesh::io::cgns
