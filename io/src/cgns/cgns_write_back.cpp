// hotmesh io: writing a moved mesh back into a copy of its CGNS file (cgns_write_back.hpp).
// The copy keeps every node of the input (bases, zones, sections, BCs, families,
// connectivity, flow solutions, user data); cg_coord_write in modify mode replaces each
// coordinate array with one of the same name, data type and size.
#include "cgns/cgns_write_back.hpp"

#include <fmt/format.h>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/atomic_file.hpp"

namespace hotmesh::io::cgns {
namespace {

struct ZoneCoordinates {
  int index = 0;
  std::string name;
  NodeId first_node = 0;
  std::size_t node_count = 0;
  std::vector<std::string> names;
  std::vector<CGNS_ENUMT(DataType_t)> types;
};

class CgnsWriteBack final : public MeshWriteBack {
 public:
  CgnsWriteBack(std::filesystem::path input, int base, std::vector<ZoneCoordinates> zones,
                std::vector<NodeId> global_of_raw)
      : input_(std::move(input)), base_(base), zones_(std::move(zones)), global_of_raw_(std::move(global_of_raw)) {}

  std::vector<std::string> output_names() const override { return {"deformed.cgns"}; }

  std::vector<std::filesystem::path> write(const std::filesystem::path& folder, std::span<const geometry::Vec3> points,
                                           const WriteBackOptions&) const override {
    const std::filesystem::path target = folder / "deformed.cgns";
    AtomicPath out(target);
    std::error_code ec;
    std::filesystem::copy_file(input_, out.temporary(), std::filesystem::copy_options::overwrite_existing, ec);
    if (ec) throw InputError::in(input_.string(), "cannot copy the CGNS file to " + target.string() + ": " + ec.message());
    File file(out.temporary(), CG_MODE_MODIFY);
    for (const ZoneCoordinates& zone : zones_) write_zone(file, zone, points);
    file.close();
    out.commit();
    return {target};
  }

 private:
  void write_zone(const File& file, const ZoneCoordinates& zone, std::span<const geometry::Vec3> points) const {
    std::vector<double> values(zone.node_count);
    std::vector<float> singles;
    for (std::size_t c = 0; c < zone.names.size(); ++c) {
      const std::size_t axis = static_cast<std::size_t>(zone.names[c].back() - 'X');  // CoordinateX/Y/Z
      for (std::size_t n = 0; n < zone.node_count; ++n) {
        const auto global = global_of_raw_[static_cast<std::size_t>(zone.first_node) + n];
        const geometry::Vec3& p = points[static_cast<std::size_t>(global)];
        values[n] = axis == 0 ? p.x : (axis == 1 ? p.y : p.z);
      }
      const void* data = values.data();
      if (zone.types[c] == CGNS_ENUMV(RealSingle)) {
        singles.assign(values.begin(), values.end());
        data = singles.data();
      }
      int index = 0;
      file.check(cg_coord_write(file.fn(), base_, zone.index, zone.types[c], zone.names[c].c_str(), data, &index),
                 fmt::format("zone '{}': writing {}", zone.name, zone.names[c]));
    }
  }

  std::filesystem::path input_;
  int base_;
  std::vector<ZoneCoordinates> zones_;
  std::vector<NodeId> global_of_raw_;
};

}  // namespace

std::shared_ptr<const MeshWriteBack> make_write_back(const std::filesystem::path& input, const RawMesh& raw,
                                                     std::vector<NodeId> global_of_raw) {
  std::vector<ZoneCoordinates> zones;
  for (const ZoneRecord& z : raw.zones) {
    for (const auto type : z.coordinate_types) {
      if (type != CGNS_ENUMV(RealSingle) && type != CGNS_ENUMV(RealDouble)) {
        throw InputError::in(raw.file, fmt::format("zone '{}' stores its coordinates as {}: hotmesh writes back "
                                                   "RealSingle and RealDouble coordinates",
                                                   z.name, cg_DataTypeName(type)));
      }
    }
    zones.push_back({z.index, z.name, z.first_node, z.node_count, z.coordinate_names, z.coordinate_types});
  }
  return std::make_shared<CgnsWriteBack>(std::filesystem::absolute(input), raw.base, std::move(zones),
                                         std::move(global_of_raw));
}

}  // namespace hotmesh::io::cgns
