// hotmesh io: the OpenFOAM write-back (see hotmesh/io/foam.hpp). The points file is rewritten
// from the one read: its header and whatever follows the list kept byte for byte, the list
// itself in the same form (ASCII with shortest round-trip numbers, or binary with the same
// scalar size), gzipped again if it was; only the file's points (not the centres added for
// polyhedra). The other polyMesh files are copied unchanged.
#include <charconv>
#include <cstring>

#include <fmt/format.h>

#include "foam/foam_write_back.hpp"
#include "gzip.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/foam.hpp"

namespace hotmesh::io {
namespace fs = std::filesystem;

namespace {

/// An OpenFOAM time name: a non-negative number such as 0.001, 5 or 1e-05.
bool is_time_name(std::string_view time) {
  if (time.empty() || time.front() < '0' || time.front() > '9') return false;
  double value = 0.0;
  const auto [end, ec] = std::from_chars(time.data(), time.data() + time.size(), value);
  return ec == std::errc() && end == time.data() + time.size();
}

}  // namespace

fs::path foam_time_folder(const fs::path& mesh_path, std::string_view time) {
  if (!is_time_name(time)) {
    throw InputError::in("--foam-time", fmt::format("'{}' is not a time folder's name: give a number such as 0.001 "
                                                    "(the moved points go to <case>/<time>/polyMesh)",
                                                    time));
  }
  std::error_code ec;
  const fs::path polymesh = fs::weakly_canonical(foam_mesh_folder(mesh_path), ec);
  const fs::path constant = polymesh.parent_path();
  if (ec || polymesh.filename() != "polyMesh" || constant.filename() != "constant") {
    throw InputError::in("--foam-time",
                         fmt::format("the mesh {} is not a case's constant/polyMesh, so there is no case "
                                     "folder to write a time folder into",
                                     mesh_path.string()));
  }
  return constant.parent_path() / std::string(time) / "polyMesh";
}

namespace foam {
namespace {

void make_folder(const fs::path& folder) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw InputError::in(folder.string(), "cannot create the folder: " + ec.message());
}

void append_scalar(std::string& out, double value, int bytes) {
  char raw[8];
  if (bytes == 4) {
    const auto f = static_cast<float>(value);
    std::memcpy(raw, &f, 4);
  } else {
    std::memcpy(raw, &value, 8);
  }
  out.append(raw, static_cast<std::size_t>(bytes));
}

std::string points_list(std::span<const geometry::Vec3> points, const FoamHeader& header) {
  std::string out = fmt::format("{}\n(", points.size());
  if (header.binary) {
    out.reserve(out.size() + points.size() * 3 * static_cast<std::size_t>(header.scalar_bytes) + 1);
    for (const geometry::Vec3& p : points) {
      for (const double c : {p.x, p.y, p.z}) append_scalar(out, c, header.scalar_bytes);
    }
  } else {
    out.push_back('\n');
    auto it = std::back_inserter(out);
    for (const geometry::Vec3& p : points) fmt::format_to(it, "({} {} {})\n", p.x, p.y, p.z);
  }
  out.push_back(')');
  return out;
}

/// The header with its `location "..."` entry (if any) set to `location`.
std::string relocated(std::string_view header, const std::string& location) {
  const std::size_t key = header.find("location");
  const std::size_t open = key == std::string_view::npos ? key : header.find('"', key);
  const std::size_t close = open == std::string_view::npos ? open : header.find('"', open + 1);
  if (close == std::string_view::npos) return std::string(header);
  return std::string(header.substr(0, open + 1)) + location + std::string(header.substr(close));
}

class FoamWriteBack final : public MeshWriteBack {
 public:
  explicit FoamWriteBack(FoamWriteBackData data) : d_(std::move(data)) {}

  std::vector<std::string> output_names() const override {
    std::vector<std::string> names{"polyMesh/" + d_.points.name};
    for (const std::string& name : d_.copied_files) names.push_back("polyMesh/" + name);
    return names;
  }

  std::vector<fs::path> write(const fs::path& folder, std::span<const geometry::Vec3> points,
                              const WriteBackOptions& options) const override {
    const std::vector<geometry::Vec3> moved = foam_points(points);
    std::vector<fs::path> written;
    const fs::path out = folder / "polyMesh";
    make_folder(out);
    write_file_atomically(out / d_.points.name, points_file(moved, std::nullopt));
    written.push_back(out / d_.points.name);
    for (const std::string& name : d_.copied_files) {
      write_file_atomically(out / name, read_file(d_.polymesh / name));
      written.push_back(out / name);
    }
    if (options.foam_time) {
      const fs::path time_folder = foam_time_folder(d_.polymesh, *options.foam_time);
      make_folder(time_folder);
      write_file_atomically(time_folder / d_.points.name, points_file(moved, *options.foam_time + "/polyMesh"));
      written.push_back(time_folder / d_.points.name);
    }
    return written;
  }

 private:
  /// One point per OpenFOAM point: 2D nodes mapped back to both planes; in 3D the file's
  /// points, without the centres added for polyhedra.
  std::vector<geometry::Vec3> foam_points(std::span<const geometry::Vec3> points) const {
    if (d_.map.empty()) return {points.begin(), points.begin() + static_cast<std::ptrdiff_t>(d_.file_points)};
    std::vector<geometry::Vec3> out(d_.map.node.size());
    for (std::size_t q = 0; q < out.size(); ++q) {
      const geometry::Vec3& p = points[static_cast<std::size_t>(d_.map.node[q])];
      out[q] = d_.map.frames[d_.map.plane[q]].at(p);
    }
    return out;
  }

  std::string points_file(std::span<const geometry::Vec3> points, const std::optional<std::string>& location) const {
    const std::string_view content = d_.points.content;
    const std::string_view header = content.substr(0, d_.points.list_begin);
    std::string text = location ? relocated(header, *location) : std::string(header);
    text += points_list(points, d_.points.header);
    text += content.substr(d_.points.list_end);
    return d_.points.gzipped ? detail::gzip(text) : text;
  }

  FoamWriteBackData d_;
};

}  // namespace

std::shared_ptr<const MeshWriteBack> make_foam_write_back(FoamWriteBackData data) {
  return std::make_shared<FoamWriteBack>(std::move(data));
}

}  // namespace foam
}  // namespace hotmesh::io
