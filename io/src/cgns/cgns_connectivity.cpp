// hotmesh io: the connectivity of CGNS zones, as pairs of raw nodes that are one node.
// GridConnectivity1to1_t (structured): the point of index I in the zone's range is the donor
// point T (I - begin) + donor_begin, T the transform matrix (column a: +-e_|t_a|).
// GridConnectivity_t of type Abutting1to1 at vertices: point k of the zone's point set is
// point k of the donor's. Other connectivity (overset, non-matching abutting) is not a node
// match: it is reported and left alone. A periodic connection (GridConnectivityProperty with
// Periodic: a rotation or translation) joins no nodes either: its side of the zone becomes a
// patch named as the connection, for a periodic role in the case file.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdlib>
#include <limits>

#include "cgns/cgns_reader.hpp"
#include "hotmesh/core/input_error.hpp"

namespace hotmesh::io::cgns {
namespace {

void check_inside(const RawMesh& raw, const ZoneRecord& zone, const cgsize_t* point, int dims, const std::string& where) {
  for (int a = 0; a < dims; ++a) {
    const cgsize_t limit = dims == 1 ? static_cast<cgsize_t>(zone.node_count) : zone.vertices[static_cast<std::size_t>(a)];
    if (point[a] < 1 || point[a] > limit) {
      throw InputError::in(raw.file, fmt::format("{} reaches node index {} of direction {} of zone '{}', which has {}",
                                                 where, point[a], a + 1, zone.name, limit));
    }
  }
}

/// The nodes of a periodic connection's side as a patch named after it.
void add_periodic_side(RawMesh& raw, std::size_t z, const std::string& name, const std::vector<cgsize_t>& points,
                       int dims) {
  RawBc bc;
  bc.patch = name;
  bc.where = fmt::format("zone '{}' periodic connection '{}'", raw.zones[z].name, name);
  bc.zone = z;
  bc.by_points = true;
  for (std::size_t p = 0; p < points.size(); p += static_cast<std::size_t>(dims)) {
    check_inside(raw, raw.zones[z], points.data() + p, dims, bc.where);
    bc.nodes.push_back(raw_node(raw.zones[z], points.data() + p, dims));
  }
  raw.bcs.push_back(std::move(bc));
}

void join_one_to_one(const File& file, RawMesh& raw, std::size_t z, int c) {
  ZoneRecord& zone = raw.zones[z];
  const int d = index_dimension(raw, zone);
  const OneToOne connection = read_one_to_one(file, raw.base, zone.index, c, d, zone.name);
  const auto& [name, donor_name, range, donor_range, transform] = connection;
  const std::string where = fmt::format("zone '{}' connection '{}'", zone.name, name);
  const ZoneRecord& donor = raw.zones[raw.zone_named(donor_name, where)];
  for (int a = 0; a < d; ++a) {
    const int t = std::abs(transform[static_cast<std::size_t>(a)]);
    if (t < 1 || t > d) throw InputError::in(raw.file, fmt::format("{} has transform entry {}", where, transform[static_cast<std::size_t>(a)]));
  }
  const std::vector<cgsize_t> points = expand_point_set(raw, CGNS_ENUMV(PointRange), {range.begin(), range.begin() + 2 * d},
                                                        d, node_limits(zone), where);
  std::array<float, 3> center{}, angle{}, translation{};
  if (cg_1to1_periodic_read(file.fn(), raw.base, zone.index, c, center.data(), angle.data(), translation.data()) == CG_OK) {
    add_periodic_side(raw, z, name, points, d);
    return;
  }
  zone.has_connectivity = true;
  for (std::size_t p = 0; p < points.size(); p += static_cast<std::size_t>(d)) {
    std::array<cgsize_t, 3> q{1, 1, 1};
    for (int a = 0; a < d; ++a) {
      const int t = transform[static_cast<std::size_t>(a)];
      const auto b = static_cast<std::size_t>(std::abs(t) - 1);
      const std::int64_t index = std::int64_t{donor_range[b]} + (t > 0 ? 1 : -1) * (std::int64_t{points[p + static_cast<std::size_t>(a)]} -
                                                                               range[static_cast<std::size_t>(a)]);
      q[b] = static_cast<cgsize_t>(std::clamp<std::int64_t>(index, 0, std::numeric_limits<cgsize_t>::max()));
    }
    check_inside(raw, zone, points.data() + p, d, where);
    check_inside(raw, donor, q.data(), d, where);
    raw.joined.emplace_back(raw_node(zone, points.data() + p, d), raw_node(donor, q.data(), d));
  }
}

void read_general(const File& file, RawMesh& raw, std::size_t z, int c) {
  ZoneRecord& zone = raw.zones[z];
  Label name{}, donor_name{};
  CGNS_ENUMT(GridLocation_t) location{};
  CGNS_ENUMT(GridConnectivityType_t) type{};
  CGNS_ENUMT(PointSetType_t) set{}, donor_set{};
  CGNS_ENUMT(ZoneType_t) donor_type{};
  CGNS_ENUMT(DataType_t) donor_data_type{};
  cgsize_t count = 0, donor_count = 0;
  file.check(cg_conn_info(file.fn(), raw.base, zone.index, c, name, &location, &type, &set, &count, donor_name,
                          &donor_type, &donor_set, &donor_data_type, &donor_count),
             fmt::format("zone '{}': reading connection {}", zone.name, c));
  const std::string where = fmt::format("zone '{}' connection '{}'", zone.name, name);
  if (type != CGNS_ENUMV(Abutting1to1) || location != CGNS_ENUMV(Vertex)) {
    spdlog::warn("{}: {} is {} at {}: not a node-to-node match, left alone", raw.file, where,
                 cg_GridConnectivityTypeName(type), cg_GridLocationName(location));
    return;
  }
  const ZoneRecord& donor = raw.zones[raw.zone_named(donor_name, where)];
  const int d = index_dimension(raw, zone), dd = index_dimension(raw, donor);
  double id = 0;
  file.check(cg_conn_id(file.fn(), raw.base, zone.index, c, &id), fmt::format("{}: finding its node", where));
  check_point_set(file, id, cg_PointSetTypeName(set), d, count, where);
  check_point_set(file, id, cg_PointSetTypeName(donor_set), dd, donor_count, where);
  std::vector<cgsize_t> data(static_cast<std::size_t>(count) * static_cast<std::size_t>(d));
  std::vector<cgsize_t> donor_data(static_cast<std::size_t>(donor_count) * static_cast<std::size_t>(dd));
  file.check(cg_conn_read(file.fn(), raw.base, zone.index, c, data.data(), CGNS_ENUMV(Integer), donor_data.data()),
             fmt::format("{}: reading its points", where));
  const auto points = expand_point_set(raw, set, data, d, node_limits(zone), where);
  const auto donors = expand_point_set(raw, donor_set, donor_data, dd, node_limits(donor), where + " (donor side)");
  std::array<float, 3> center{}, angle{}, translation{};
  if (cg_conn_periodic_read(file.fn(), raw.base, zone.index, c, center.data(), angle.data(), translation.data()) == CG_OK) {
    add_periodic_side(raw, z, name, points, d);
    return;
  }
  zone.has_connectivity = true;
  const std::size_t n = points.size() / static_cast<std::size_t>(d);
  if (donors.size() / static_cast<std::size_t>(dd) != n) {
    throw InputError::in(raw.file, fmt::format("{} lists {} points and {} donor points", where, n,
                                               donors.size() / static_cast<std::size_t>(dd)));
  }
  for (std::size_t k = 0; k < n; ++k) {
    check_inside(raw, zone, points.data() + k * static_cast<std::size_t>(d), d, where);
    check_inside(raw, donor, donors.data() + k * static_cast<std::size_t>(dd), dd, where);
    raw.joined.emplace_back(raw_node(zone, points.data() + k * static_cast<std::size_t>(d), d),
                            raw_node(donor, donors.data() + k * static_cast<std::size_t>(dd), dd));
  }
}

}  // namespace

void read_connectivity(const File& file, RawMesh& raw, std::size_t z) {
  ZoneRecord& zone = raw.zones[z];
  int one_to_one = 0, general = 0;
  file.check(cg_n1to1(file.fn(), raw.base, zone.index, &one_to_one), fmt::format("zone '{}': reading its 1-to-1 connections", zone.name));
  file.check(cg_nconns(file.fn(), raw.base, zone.index, &general), fmt::format("zone '{}': reading its connections", zone.name));
  for (int c = 1; c <= one_to_one; ++c) join_one_to_one(file, raw, z, c);
  for (int c = 1; c <= general; ++c) read_general(file, raw, z, c);
}

}  // namespace hotmesh::io::cgns
