// hotmesh io: what a CGNS file holds, for `hotmesh info` (describe_cgns in cgns.hpp).
#include <fmt/format.h>

#include "cgns/cgns_library.hpp"
#include "hotmesh/io/cgns.hpp"

namespace hotmesh::io::cgns {
namespace {

using Summary = CgnsSummary;

std::vector<Summary::Section> sections(const File& file, int b, int z) {
  int count = 0;
  file.check(cg_nsections(file.fn(), b, z, &count), "reading sections");
  std::vector<Summary::Section> out;
  for (int s = 1; s <= count; ++s) {
    Label name{};
    CGNS_ENUMT(ElementType_t) type{};
    cgsize_t first = 0, last = 0;
    int boundary = 0, parent = 0;
    file.check(cg_section_read(file.fn(), b, z, s, name, &type, &first, &last, &boundary, &parent), "reading a section");
    out.push_back({name, cg_ElementTypeName(type), first, last});
  }
  return out;
}

std::vector<Summary::Bc> bcs(const File& file, int b, int z) {
  int count = 0;
  file.check(cg_nbocos(file.fn(), b, z, &count), "reading BCs");
  std::vector<Summary::Bc> out;
  for (int c = 1; c <= count; ++c) {
    Label name{};
    CGNS_ENUMT(BCType_t) type{};
    CGNS_ENUMT(PointSetType_t) set{};
    cgsize_t points = 0, normals = 0;
    std::array<int, 3> normal_index{};
    CGNS_ENUMT(DataType_t) normal_type{};
    int datasets = 0;
    file.check(cg_boco_info(file.fn(), b, z, c, name, &type, &set, &points, normal_index.data(), &normals, &normal_type,
                            &datasets),
               "reading a BC");
    CGNS_ENUMT(GridLocation_t) location = CGNS_ENUMV(Vertex);
    file.check(cg_boco_gridlocation_read(file.fn(), b, z, c, &location), "reading a BC's location");
    out.push_back({name, cg_BCTypeName(type), cg_GridLocationName(location), cg_PointSetTypeName(set),
                   bc_family(file, b, z, c), points});
  }
  return out;
}

std::vector<Summary::Connection> connections(const File& file, int b, int z, std::string_view zone) {
  std::vector<Summary::Connection> out;
  int one_to_one = 0, general = 0, index_dimension = 0;
  file.check(cg_n1to1(file.fn(), b, z, &one_to_one), "reading 1-to-1 connections");
  file.check(cg_nconns(file.fn(), b, z, &general), "reading connections");
  file.check(cg_index_dim(file.fn(), b, z, &index_dimension), "reading a zone's index dimension");
  for (int c = 1; c <= one_to_one; ++c) {
    const OneToOne connection = read_one_to_one(file, b, z, c, index_dimension, zone);
    out.push_back({connection.name, "1to1", connection.donor});
  }
  for (int c = 1; c <= general; ++c) {
    Label name{}, donor{};
    CGNS_ENUMT(GridLocation_t) location{};
    CGNS_ENUMT(GridConnectivityType_t) type{};
    CGNS_ENUMT(PointSetType_t) set{}, donor_set{};
    CGNS_ENUMT(ZoneType_t) donor_type{};
    CGNS_ENUMT(DataType_t) donor_data{};
    cgsize_t points = 0, donor_points = 0;
    file.check(cg_conn_info(file.fn(), b, z, c, name, &location, &type, &set, &points, donor, &donor_type, &donor_set,
                            &donor_data, &donor_points),
               "reading a connection");
    out.push_back({name, cg_GridConnectivityTypeName(type), donor});
  }
  return out;
}

Summary::Zone zone_summary(const File& file, int b, int z, int cell_dimension) {
  Summary::Zone zone;
  Label name{};
  std::array<cgsize_t, 9> size{};
  file.check(cg_zone_read(file.fn(), b, z, name, size.data()), fmt::format("reading zone {}", z));
  CGNS_ENUMT(ZoneType_t) type{};
  file.check(cg_zone_type(file.fn(), b, z, &type), "reading a zone's type");
  zone.name = name;
  zone.type = cg_ZoneTypeName(type);
  const int entries = type == CGNS_ENUMV(Structured) ? 3 * cell_dimension : 3;
  zone.size.assign(size.begin(), size.begin() + entries);
  zone.sections = sections(file, b, z);
  zone.bcs = bcs(file, b, z);
  zone.connections = connections(file, b, z, zone.name);
  file.check(cg_nsols(file.fn(), b, z, &zone.solutions), "reading flow solutions");
  return zone;
}

}  // namespace
}  // namespace hotmesh::io::cgns

namespace hotmesh::io {

CgnsSummary describe_cgns(const std::filesystem::path& path, const CgnsReadOptions& options) {
  if (options.check_in_child) cgns::check_in_child(path.string(), [&path] { describe_cgns(path, {false}); });
  const cgns::File file(path, CG_MODE_READ);
  CgnsSummary summary;
  int file_type = CG_FILE_NONE;
  cg_get_file_type(file.fn(), &file_type);
  summary.file_type = file_type == CG_FILE_HDF5 ? "HDF5" : "ADF";
  int bases = 0;
  file.check(cg_nbases(file.fn(), &bases), "reading the number of bases");
  for (int b = 1; b <= bases; ++b) {
    CgnsSummary::Base& base = summary.bases.emplace_back();
    cgns::Label name{};
    file.check(cg_base_read(file.fn(), b, name, &base.cell_dimension, &base.physical_dimension), "reading a base");
    base.name = name;
    int zones = 0, families = 0;
    file.check(cg_nzones(file.fn(), b, &zones), "reading the number of zones");
    for (int z = 1; z <= zones; ++z) base.zones.push_back(cgns::zone_summary(file, b, z, base.cell_dimension));
    file.check(cg_nfamilies(file.fn(), b, &families), "reading families");
    for (int f = 1; f <= families; ++f) {
      cgns::Label family{};
      int bcs = 0, geometries = 0;
      file.check(cg_family_read(file.fn(), b, f, family, &bcs, &geometries), "reading a family");
      base.families.emplace_back(family);
    }
  }
  return summary;
}

}  // namespace hotmesh::io
