// hotmesh io (private): the pieces of the CGNS reader. Each zone is read on its own into a
// RawMesh, its nodes numbered zone after zone ("raw" node ids); cgns_assemble.cpp then joins
// the zones (connectivity pairs, or coincident boundary nodes), numbers the unique nodes and
// turns the boundary conditions into patches.
//   cgns_zone_unstructured.cpp  sections and BCs of unstructured zones
//   cgns_zone_structured.cpp    cells, BCs and 1-to-1 interfaces of structured zones
//   cgns_connectivity.cpp       GridConnectivity_t point lists (both zone types)
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "cgns/cgns_library.hpp"
#include "hotmesh/mesh/mesh.hpp"

namespace hotmesh::io::cgns {

using mesh::NodeId;

/// Where a zone's nodes and cells sit in the RawMesh, and what write-back needs of it.
struct ZoneRecord {
  std::string name;
  int index = 0;                         ///< the zone's number in its base (1-based)
  bool structured = false;
  std::array<cgsize_t, 3> vertices{1, 1, 1};  ///< structured: nodes along i, j, k
  NodeId first_node = 0;                 ///< raw id of the zone's node 1
  std::size_t node_count = 0;
  std::size_t first_cell = 0, cell_count = 0;
  std::vector<std::string> coordinate_names;  ///< CoordinateX, CoordinateY [, CoordinateZ]
  std::vector<CGNS_ENUMT(DataType_t)> coordinate_types;
  bool has_connectivity = false;  ///< some connection of it matches nodes (periodic ones do not)
};

/// A boundary condition (or an unreferenced boundary face section) of one zone.
struct RawBc {
  std::string patch;   ///< the patch it belongs to: its FamilyName, else its own name
  std::string where;   ///< "zone 'Z' BC 'B'" for messages
  std::size_t zone = 0;
  bool by_points = false;
  bool from_section = false;  ///< a face section no BC names: its faces inside the mesh are dropped
  std::vector<NodeId> nodes;  ///< by_points: raw node ids
  mesh::ElementList faces;    ///< otherwise: faces in raw node ids
};

struct RawMesh {
  std::string file;
  int base = 1, dimension = 3, physical_dimension = 3;
  std::string base_name;  ///< of base `base`
  std::vector<geometry::Vec3> points;  ///< every zone's nodes, zone after zone
  mesh::ElementList cells;             ///< in raw node ids
  std::vector<ZoneRecord> zones;
  std::vector<RawBc> bcs;
  std::vector<std::pair<NodeId, NodeId>> joined;  ///< raw nodes the connectivity declares one

  std::size_t zone_named(std::string_view name, std::string_view where) const;
};

/// Reads the zone's grid coordinates (Cartesian) into raw.points and fills its record.
void read_coordinates(const File& file, RawMesh& raw, ZoneRecord& zone);
void read_unstructured_zone(const File& file, RawMesh& raw, std::size_t zone);
void read_structured_zone(const File& file, RawMesh& raw, std::size_t zone);
/// GridConnectivity1to1_t (structured) and GridConnectivity_t (Abutting1to1 point lists).
void read_connectivity(const File& file, RawMesh& raw, std::size_t zone);

/// The raw node id of zone-local 1-based index point `ijk` (index dimension entries).
NodeId raw_node(const ZoneRecord& zone, const cgsize_t* ijk, int index_dimension);
/// The zone's index dimension: 1 for unstructured zones, the base's cell dimension for
/// structured ones.
int index_dimension(const RawMesh& raw, const ZoneRecord& zone);
/// The points of a point set, index_dimension entries each: a PointRange expanded, a
/// PointList as it is. A range must lie within the zone, `limits` being the largest index along
/// each direction (its nodes); that is checked before it is expanded, so that it makes no more
/// points than the zone has. InputError "file: <where>: its PointRange ..." otherwise.
std::vector<cgsize_t> expand_point_set(const RawMesh& raw, CGNS_ENUMT(PointSetType_t) type,
                                       const std::vector<cgsize_t>& data, int index_dimension,
                                       const std::array<cgsize_t, 3>& limits, std::string_view where);
/// The largest index along each direction of the zone: its nodes along i, j, k (structured),
/// or its node count (unstructured).
std::array<cgsize_t, 3> node_limits(const ZoneRecord& zone);

/// A BC_t of a zone as the file gives it: where it is, its point set, the patch it names.
struct BcPoints {
  std::string where;  ///< "zone 'Z' BC 'B'"
  std::string patch;  ///< its FamilyName, else its name
  CGNS_ENUMT(PointSetType_t) set{};
  CGNS_ENUMT(GridLocation_t) location = CGNS_ENUMV(Vertex);
  std::vector<cgsize_t> data;  ///< the point set's entries, index_dimension per point
};
/// The BC's point set, checked to be stored as the zone's index dimension x its points.
BcPoints read_bc_points(const File& file, const RawMesh& raw, const ZoneRecord& zone, int bc);

/// The mesh the zones make together (nodes joined, patches named); global_of_raw gets the
/// mesh node of every raw node.
mesh::Mesh assemble(const RawMesh& raw, std::vector<NodeId>& global_of_raw);

}  // namespace hotmesh::io::cgns
