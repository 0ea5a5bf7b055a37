// hotmesh io: writing a moved mesh back into a copy of its CGNS file (cgns_write_back.hpp).
// The copy keeps every node of the input (bases, zones, sections, BCs, families,
// connectivity, flow solutions, user data, the CGNSLibraryVersion) as the input has it: the
// coordinate arrays' data is overwritten at the node level (cgns_io.h), in place, in the
// array's own data type and size. Not through the mid-level library: opened in modify mode,
// it rewrites a file of an older version into its own on closing (the CGNSLibraryVersion,
// an ElementStartOffset added to each section of a file written before CGNS 3.4).
#include "cgns/cgns_write_back.hpp"

#include <cgns_io.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <string_view>

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

/// A CGNS file opened at the node level to overwrite arrays; holds the library's lock.
/// Messages name `source`, the file it is a copy of.
class NodeFile {
 public:
  NodeFile(const std::filesystem::path& path, std::string source) : lock_(library_lock()), name_(std::move(source)) {
    check(cgio_open_file(path.c_str(), CGIO_MODE_MODIFY, CGIO_FILE_NONE, &cgio_), "cannot open the copy");
    check(cgio_get_root_id(cgio_, &root_), "cannot read the copy's root node");
  }
  ~NodeFile() {
    if (cgio_ > 0) cgio_close_file(cgio_);
  }
  NodeFile(const NodeFile&) = delete;
  NodeFile& operator=(const NodeFile&) = delete;

  /// Overwrites the data of the array at `path` (from the root), which must store `count`
  /// values of `type` ("R4", "R8"), with `data`.
  void overwrite(const std::string& path, const char* type, std::size_t count, const void* data) {
    const double id = node_in_this_file(path);
    char stored_type[CGIO_MAX_DATATYPE_LENGTH + 1] = {};
    int rank = 0;
    std::array<cgsize_t, CGIO_MAX_DIMENSIONS> dimensions{};
    check(cgio_get_data_type(cgio_, id, stored_type), "reading the data type of " + path);
    check(cgio_get_dimensions(cgio_, id, &rank, dimensions.data()), "reading the dimensions of " + path);
    std::int64_t stored = rank > 0 ? 1 : 0;
    for (int d = 0; d < rank; ++d) stored *= dimensions[static_cast<std::size_t>(d)];
    if (std::string_view(stored_type, 2) != type || stored != static_cast<std::int64_t>(count)) {
      throw InputError::in(name_, fmt::format("{} stores {} values of {}, the mesh read from it {} of {}", path, stored,
                                              std::string_view(stored_type, 2), count, type));
    }
    check(cgio_write_all_data(cgio_, id, data), "writing " + path);
  }

  /// The node at `path`, reached name by name: a link on the way would lead into another
  /// file (which is not the copy's to change), and is refused.
  double node_in_this_file(const std::string& path) const {
    double id = root_;
    std::size_t start = 1;
    while (start <= path.size()) {
      const std::size_t end = std::min(path.find('/', start), path.size());
      const std::string name = path.substr(start, end - start);
      double child = 0;
      check(cgio_get_node_id(cgio_, id, name.c_str(), &child), path + " is not in the copy");
      int link = 0;
      check(cgio_is_link(cgio_, child, &link), "reading " + path);
      if (link > 0) {
        throw InputError::in(name_, fmt::format("{} is a link into another file: hotmesh writes the moved "
                                                "coordinates into deformed.cgns only (store them in the file)",
                                                path.substr(0, end)));
      }
      id = child;
      start = end + 1;
    }
    return id;
  }

  void close() {
    const int cgio = cgio_;
    cgio_ = 0;
    check(cgio_close_file(cgio), "cannot close the copy");
  }

 private:
  void check(int status, const std::string& what) const {
    if (status == CGIO_ERR_NONE) return;
    char message[CGIO_MAX_ERROR_LENGTH + 1] = {};
    cgio_error_message(message);
    throw InputError::in(name_, what + ": " + message);
  }

  std::unique_lock<std::recursive_mutex> lock_;
  std::string name_;
  int cgio_ = 0;
  double root_ = 0;
};

class CgnsWriteBack final : public MeshWriteBack {
 public:
  CgnsWriteBack(std::filesystem::path input, std::string base, std::vector<ZoneCoordinates> zones,
                std::vector<NodeId> global_of_raw)
      : input_(std::move(input)),
        base_(std::move(base)),
        zones_(std::move(zones)),
        global_of_raw_(std::move(global_of_raw)) {}

  std::vector<std::string> output_names() const override { return {"deformed.cgns"}; }

  std::vector<std::filesystem::path> write(const std::filesystem::path& folder, std::span<const geometry::Vec3> points,
                                           const WriteBackOptions&) const override {
    const std::filesystem::path target = folder / "deformed.cgns";
    AtomicPath out(target);
    std::error_code ec;
    std::filesystem::copy_file(input_, out.temporary(), std::filesystem::copy_options::overwrite_existing, ec);
    if (ec) throw InputError::in(input_.string(), "cannot copy the CGNS file to " + target.string() + ": " + ec.message());
    NodeFile file(out.temporary(), input_.string());
    for (const ZoneCoordinates& zone : zones_) write_zone(file, zone, points);
    file.close();
    out.commit();
    return {target};
  }

 private:
  void write_zone(NodeFile& file, const ZoneCoordinates& zone, std::span<const geometry::Vec3> points) const {
    std::vector<double> values(zone.node_count);
    std::vector<float> singles;
    for (std::size_t c = 0; c < zone.names.size(); ++c) {
      const std::size_t axis = static_cast<std::size_t>(zone.names[c].back() - 'X');  // CoordinateX/Y/Z
      for (std::size_t n = 0; n < zone.node_count; ++n) {
        const auto global = global_of_raw_[static_cast<std::size_t>(zone.first_node) + n];
        const geometry::Vec3& p = points[static_cast<std::size_t>(global)];
        values[n] = axis == 0 ? p.x : (axis == 1 ? p.y : p.z);
      }
      const std::string path = "/" + base_ + "/" + zone.name + "/GridCoordinates/" + zone.names[c];
      if (zone.types[c] == CGNS_ENUMV(RealSingle)) {
        singles.assign(values.begin(), values.end());
        file.overwrite(path, "R4", zone.node_count, singles.data());
      } else {
        file.overwrite(path, "R8", zone.node_count, values.data());
      }
    }
  }

  std::filesystem::path input_;
  std::string base_;
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
  return std::make_shared<CgnsWriteBack>(std::filesystem::absolute(input), raw.base_name, std::move(zones),
                                         std::move(global_of_raw));
}

}  // namespace hotmesh::io::cgns
