// hotmesh io (internal): what the OpenFOAM write-back keeps of the mesh it read: the points
// file as read (its header and where its list is), the other polyMesh files to copy, and, for
// a 2D case, where each OpenFOAM point goes from the moved 2D mesh.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "foam/foam_file.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "hotmesh/mesh/solver_quality.hpp"

namespace hotmesh::io::foam {

/// A plane of a 2D case: the 2D point (x, y) is origin + x u + y v in it.
using PlaneFrame = mesh::PlaneMap;

/// For a 2D case, each OpenFOAM point's 2D node and plane (0 back, 1 front); empty for 3D
/// (point i is node i).
struct PointMap {
  std::vector<std::int32_t> node;
  std::vector<std::uint8_t> plane;
  std::array<PlaneFrame, 2> frames{};
  bool empty() const { return node.empty(); }
};

struct PointsFile {
  std::string name;  ///< "points" or "points.gz"
  bool gzipped = false;
  std::string content;  ///< uncompressed
  FoamHeader header;
  std::size_t list_begin = 0, list_end = 0;  ///< the points list within content
};

struct FoamWriteBackData {
  std::filesystem::path polymesh;  ///< the folder read
  PointsFile points;
  std::vector<std::string> copied_files;  ///< the other files of the folder, copied unchanged
  PointMap map;
  std::size_t file_points = 0;  ///< 3D: the points the file has (the mesh's first)
};

std::shared_ptr<const MeshWriteBack> make_foam_write_back(FoamWriteBackData data);

}  // namespace hotmesh::io::foam
