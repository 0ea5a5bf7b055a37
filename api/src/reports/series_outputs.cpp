// hotmesh api: the motion as ParaView time series (deformed.pvd, walls.pvd).
#include "hotmesh/api/series_outputs.hpp"

#include <fstream>
#include <optional>

#include <fmt/format.h>

#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/setup/deflected_walls.hpp"
#include "hotmesh/io/vtu.hpp"

namespace hotmesh::api {
namespace {

constexpr const char* kSeriesFolder = "series";

/// The value of attribute `name` in an XML line (`name="value"`), or nothing.
std::optional<std::string> attribute(const std::string& line, const std::string& name) {
  const std::string open = " " + name + "=\"";
  const auto begin = line.find(open);
  if (begin == std::string::npos) return std::nullopt;
  const auto first = begin + open.size();
  const auto end = line.find('"', first);
  if (end == std::string::npos) return std::nullopt;
  return line.substr(first, end - first);
}

/// The (time, file) pairs of a .pvd this writer wrote, in order; none if there is no such file.
std::vector<std::pair<double, std::string>> read_collection(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::pair<double, std::string>> entries;
  for (std::string line; std::getline(in, line);) {
    const auto time = attribute(line, "timestep");
    const auto file = attribute(line, "file");
    if (line.find("<DataSet") == std::string::npos || !time || !file) continue;
    entries.emplace_back(std::stod(*time), *file);
  }
  return entries;
}

void write_collection(const std::filesystem::path& path, const std::vector<std::pair<double, std::string>>& entries) {
  io::AtomicFile file(path);
  std::ostream& out = file.stream();
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <Collection>\n";
  for (const auto& [time, name] : entries) out << fmt::format("    <DataSet timestep=\"{}\" file=\"{}\"/>\n", time, name);
  out << "  </Collection>\n</VTKFile>\n";
  file.commit();
}

}  // namespace

SeriesWriter::SeriesWriter(std::filesystem::path folder, const mesh::Mesh& mesh, const mesh::Extrusion& layer,
                           std::span<const deform::PatchMotion> motions, double resumed_time)
    : folder_(std::move(folder)), mesh_(mesh), layer_(layer), motions_(motions) {
  if (resumed_time < 0.0) return;
  const auto meshes = read_collection(folder_ / "deformed.pvd");
  const auto walls = read_collection(folder_ / "walls.pvd");
  for (std::size_t i = 0; i < meshes.size() && i < walls.size(); ++i) {
    if (meshes[i].first > resumed_time) break;
    steps_.push_back({meshes[i].first, meshes[i].second, walls[i].second});
  }
}

void SeriesWriter::add(double time, double lambda, std::span<const geometry::Vec3> points) {
  std::filesystem::create_directories(folder_ / kSeriesFolder);
  const std::size_t index = steps_.size();
  Step step{time, fmt::format("{}/mesh_{:04d}.vtu", kSeriesFolder, index),
            fmt::format("{}/walls_{:04d}.vtp", kSeriesFolder, index)};
  io::VtuFields fields = io::quality_fields(mesh_, points, layer_);
  std::vector<double> displacement(3 * points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const geometry::Vec3 d = points[i] - mesh_.points[i];
    displacement[3 * i] = d.x;
    displacement[3 * i + 1] = d.y;
    displacement[3 * i + 2] = d.z;
  }
  fields.point_data.push_back({"displacement", 3, std::move(displacement)});
  io::write_vtu(folder_ / step.mesh_file, mesh_, points, fields);
  io::write_vtp(folder_ / step.walls_file, setup::deflected_walls(mesh_, motions_, lambda));
  steps_.push_back(std::move(step));
  write_collections();
}

void SeriesWriter::write_collections() const {
  std::vector<std::pair<double, std::string>> meshes, walls;
  for (const Step& s : steps_) {
    meshes.emplace_back(s.time, s.mesh_file);
    walls.emplace_back(s.time, s.walls_file);
  }
  write_collection(folder_ / "deformed.pvd", meshes);
  write_collection(folder_ / "walls.pvd", walls);
}

}  // namespace hotmesh::api
