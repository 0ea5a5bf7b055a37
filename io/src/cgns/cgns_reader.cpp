// hotmesh io: reading a CGNS file: the base, its zones one by one, then the mesh they make
// together (cgns_reader.hpp describes the pieces).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <limits>

#include "cgns/cgns_reader.hpp"
#include "cgns/cgns_write_back.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/cgns.hpp"

namespace hotmesh::io::cgns {
namespace {

void read_base(const File& file, RawMesh& raw) {
  int bases = 0;
  file.check(cg_nbases(file.fn(), &bases), "reading the number of bases");
  if (bases < 1) throw InputError::in(file.name(), "the file has no CGNSBase_t: there is no mesh in it");
  if (bases > 1) spdlog::warn("{}: {} bases; hotmesh reads the first only", file.name(), bases);
  Label name{};
  file.check(cg_base_read(file.fn(), raw.base, name, &raw.dimension, &raw.physical_dimension), "reading base 1");
  raw.base_name = name;
  if (raw.dimension != 2 && raw.dimension != 3) {
    throw InputError::in(file.name(), fmt::format("base '{}' has cell dimension {}: hotmesh moves 2D (triangle and "
                                                  "quad) and 3D (tetrahedron, pyramid, prism and hex) meshes",
                                                  name, raw.dimension));
  }
  if (raw.physical_dimension < raw.dimension) {
    throw InputError::in(file.name(), fmt::format("base '{}' has physical dimension {} below its cell dimension {}", name,
                                                  raw.physical_dimension, raw.dimension));
  }
}

/// An unstructured zone's declared cell count against the cells its sections hold.
void check_cell_count(const File& file, const RawMesh& raw, const ZoneRecord& zone) {
  if (zone.structured) return;
  Label name{};
  std::array<cgsize_t, 9> size{};
  file.check(cg_zone_read(file.fn(), raw.base, zone.index, name, size.data()), fmt::format("reading zone '{}'", zone.name));
  if (static_cast<std::size_t>(size[1]) != zone.cell_count) {
    spdlog::warn("{}: zone '{}' declares {} cells, its sections hold {} cells ({})", file.name(), zone.name, size[1],
                 zone.cell_count, raw.dimension == 2 ? "TRI_3, QUAD_4" : "TETRA_4, PYRA_5, PENTA_6, HEXA_8");
  }
}

void read_zones(const File& file, RawMesh& raw) {
  int zones = 0;
  file.check(cg_nzones(file.fn(), raw.base, &zones), "reading the number of zones");
  if (zones < 1) throw InputError::in(file.name(), "the base has no zones: there is no mesh in it");
  raw.zones.resize(static_cast<std::size_t>(zones));
  for (int z = 1; z <= zones; ++z) {
    ZoneRecord& zone = raw.zones[static_cast<std::size_t>(z - 1)];
    zone.index = z;
    CGNS_ENUMT(ZoneType_t) type{};
    file.check(cg_zone_type(file.fn(), raw.base, z, &type), fmt::format("reading the type of zone {}", z));
    zone.structured = type == CGNS_ENUMV(Structured);
    read_coordinates(file, raw, zone);
  }
  for (std::size_t z = 0; z < raw.zones.size(); ++z) {
    raw.zones[z].first_cell = raw.cells.size();
    if (raw.zones[z].structured) {
      read_structured_zone(file, raw, z);
    } else {
      read_unstructured_zone(file, raw, z);
    }
    raw.zones[z].cell_count = raw.cells.size() - raw.zones[z].first_cell;
    check_cell_count(file, raw, raw.zones[z]);
  }
  for (std::size_t z = 0; z < raw.zones.size(); ++z) read_connectivity(file, raw, z);
}

std::vector<double> read_coordinate(const File& file, const RawMesh& raw, const ZoneRecord& zone,
                                    const std::string& name) {
  std::vector<double> values(zone.node_count);
  std::array<cgsize_t, 3> lo{1, 1, 1};
  std::array<cgsize_t, 3> hi = zone.vertices;
  if (!zone.structured) hi[0] = static_cast<cgsize_t>(zone.node_count);
  file.check(cg_coord_read(file.fn(), raw.base, zone.index, name.c_str(), CGNS_ENUMV(RealDouble), lo.data(), hi.data(),
                           values.data()),
             fmt::format("zone '{}': reading {}", zone.name, name));
  return values;
}

}  // namespace

std::size_t RawMesh::zone_named(std::string_view name, std::string_view where) const {
  for (std::size_t z = 0; z < zones.size(); ++z) {
    if (zones[z].name == name) return z;
  }
  throw InputError::in(file, fmt::format("{} names donor zone '{}', which the base does not have", where, name));
}

int index_dimension(const RawMesh& raw, const ZoneRecord& zone) { return zone.structured ? raw.dimension : 1; }

NodeId raw_node(const ZoneRecord& zone, const cgsize_t* ijk, int index_dimension) {
  if (index_dimension == 1) return zone.first_node + static_cast<NodeId>(ijk[0] - 1);
  std::int64_t local = 0;
  for (int d = index_dimension - 1; d >= 0; --d) local = local * zone.vertices[static_cast<std::size_t>(d)] + (ijk[d] - 1);
  return zone.first_node + static_cast<NodeId>(local);
}

std::array<cgsize_t, 3> node_limits(const ZoneRecord& zone) {
  if (zone.structured) return zone.vertices;
  return {static_cast<cgsize_t>(zone.node_count), 1, 1};
}

std::vector<cgsize_t> expand_point_set(const RawMesh& raw, CGNS_ENUMT(PointSetType_t) type,
                                       const std::vector<cgsize_t>& data, int index_dimension,
                                       const std::array<cgsize_t, 3>& limits, std::string_view where) {
  if (type != CGNS_ENUMV(PointRange) && type != CGNS_ENUMV(PointRangeDonor) && type != CGNS_ENUMV(ElementRange)) {
    return data;
  }
  const auto d = static_cast<std::size_t>(index_dimension);
  std::array<cgsize_t, 3> lo{1, 1, 1}, hi{1, 1, 1};
  for (std::size_t a = 0; a < d; ++a) {
    lo[a] = std::min(data[a], data[d + a]);
    hi[a] = std::max(data[a], data[d + a]);
    if (lo[a] >= 1 && hi[a] <= limits[a]) continue;
    if (d == 1) {
      throw InputError::in(raw.file, fmt::format("{}: its {} {}..{} names {} nodes, but the zone has {} nodes", where,
                                                 cg_PointSetTypeName(type), data[0], data[1],
                                                 std::int64_t{hi[0]} - lo[0] + 1, limits[0]));
    }
    throw InputError::in(raw.file, fmt::format("{}: its {} reaches index {} along {}, but the zone has {} nodes along {} "
                                               "(indices 1 to {})",
                                               where, cg_PointSetTypeName(type), lo[a] < 1 ? lo[a] : hi[a], "ijk"[a],
                                               limits[a], "ijk"[a], limits[a]));
  }
  std::vector<cgsize_t> points;
  for (std::int64_t k = lo[2]; k <= hi[2]; ++k) {  // 64 bits: a limit may be INT_MAX
    for (std::int64_t j = lo[1]; j <= hi[1]; ++j) {
      for (std::int64_t i = lo[0]; i <= hi[0]; ++i) {
        const std::array<cgsize_t, 3> p{static_cast<cgsize_t>(i), static_cast<cgsize_t>(j), static_cast<cgsize_t>(k)};
        points.insert(points.end(), p.begin(), p.begin() + index_dimension);
      }
    }
  }
  return points;
}

BcPoints read_bc_points(const File& file, const RawMesh& raw, const ZoneRecord& zone, int b) {
  Label name{};
  BcPoints bc;
  CGNS_ENUMT(BCType_t) type{};
  cgsize_t count = 0, normal_size = 0;
  std::array<int, 3> normal_index{};
  CGNS_ENUMT(DataType_t) normal_type{};
  int datasets = 0;
  file.check(cg_boco_info(file.fn(), raw.base, zone.index, b, name, &type, &bc.set, &count, normal_index.data(),
                          &normal_size, &normal_type, &datasets),
             fmt::format("zone '{}': reading BC {}", zone.name, b));
  bc.where = fmt::format("zone '{}' BC '{}'", zone.name, name);
  file.check(cg_boco_gridlocation_read(file.fn(), raw.base, zone.index, b, &bc.location),
             fmt::format("{}: reading its GridLocation", bc.where));
  if (count > 0) {  // else the BC has no point set, and the library reads none
    double id = 0;
    file.check(cg_boco_id(file.fn(), raw.base, zone.index, b, &id), fmt::format("{}: finding its node", bc.where));
    check_point_set(file, id, cg_PointSetTypeName(bc.set), index_dimension(raw, zone), count, bc.where);
  }
  bc.data.resize(static_cast<std::size_t>(count) * static_cast<std::size_t>(index_dimension(raw, zone)));
  file.check(cg_boco_read(file.fn(), raw.base, zone.index, b, bc.data.data(), nullptr),
             fmt::format("{}: reading its points", bc.where));
  bc.patch = bc_family(file, raw.base, zone.index, b);
  if (bc.patch.empty()) bc.patch = name;
  return bc;
}

void read_coordinates(const File& file, RawMesh& raw, ZoneRecord& zone) {
  Label name{};
  std::array<cgsize_t, 9> size{};
  file.check(cg_zone_read(file.fn(), raw.base, zone.index, name, size.data()), fmt::format("reading zone {}", zone.index));
  zone.name = name;
  // The library checked the coordinate arrays against these sizes when it opened the file.
  StoredArray declared;
  if (zone.structured) {
    for (int d = 0; d < raw.dimension; ++d) zone.vertices[static_cast<std::size_t>(d)] = size[static_cast<std::size_t>(d)];
    declared.dimensions.assign(zone.vertices.begin(), zone.vertices.begin() + raw.dimension);
  } else {
    declared.dimensions = {size[0]};
  }
  zone.node_count = static_cast<std::size_t>(declared.values());
  const std::size_t nodes_before = raw.points.size();
  if (declared.values() > std::numeric_limits<NodeId>::max() - static_cast<std::int64_t>(nodes_before)) {
    throw InputError::in(file.name(), fmt::format("zone '{}' has {} nodes: with the zones before it, more than the {} "
                                                  "nodes hotmesh can number",
                                                  zone.name, declared.shape(), std::numeric_limits<NodeId>::max()));
  }
  int count = 0;
  file.check(cg_ncoords(file.fn(), raw.base, zone.index, &count), fmt::format("zone '{}': reading its coordinates", zone.name));
  const std::array<const char*, 3> wanted{"CoordinateX", "CoordinateY", "CoordinateZ"};
  std::array<std::vector<double>, 3> xyz;
  for (int c = 1; c <= count; ++c) {
    Label coordinate{};
    CGNS_ENUMT(DataType_t) type{};
    file.check(cg_coord_info(file.fn(), raw.base, zone.index, c, &type, coordinate),
               fmt::format("zone '{}': reading coordinate {}", zone.name, c));
    const auto it = std::find_if(wanted.begin(), wanted.end(), [&](const char* w) { return coordinate == std::string(w); });
    if (it == wanted.end()) {
      throw InputError::in(file.name(), fmt::format("zone '{}' has coordinate '{}': hotmesh reads Cartesian coordinates "
                                                    "(CoordinateX, CoordinateY, CoordinateZ) only",
                                                    zone.name, coordinate));
    }
    zone.coordinate_names.emplace_back(coordinate);
    zone.coordinate_types.push_back(type);
    xyz[static_cast<std::size_t>(it - wanted.begin())] = read_coordinate(file, raw, zone, coordinate);
  }
  for (int d = 0; d < raw.dimension; ++d) {
    if (xyz[static_cast<std::size_t>(d)].empty()) {
      throw InputError::in(file.name(), fmt::format("zone '{}' has no {}", zone.name, wanted[static_cast<std::size_t>(d)]));
    }
  }
  zone.first_node = static_cast<NodeId>(raw.points.size());
  for (std::size_t n = 0; n < zone.node_count; ++n) {
    raw.points.push_back({xyz[0][n], xyz[1][n], xyz[2].empty() ? 0.0 : xyz[2][n]});
  }
}

}  // namespace hotmesh::io::cgns

namespace hotmesh::io {

CgnsMesh read_cgns(const std::filesystem::path& path, const CgnsReadOptions& options) {
  const auto read_raw = [&path] {
    const cgns::File file(path, CG_MODE_READ);
    cgns::RawMesh raw;
    raw.file = file.name();
    cgns::read_base(file, raw);
    cgns::read_zones(file, raw);
    return raw;
  };
  if (options.check_in_child) cgns::check_in_child(path.string(), read_raw);
  const cgns::RawMesh raw = read_raw();
  std::vector<mesh::NodeId> global_of_raw;
  CgnsMesh result{cgns::assemble(raw, global_of_raw), nullptr};
  result.write_back = cgns::make_write_back(path, raw, std::move(global_of_raw));
  return result;
}

}  // namespace hotmesh::io
