// hotmesh io: restart files (restart.hmr), section 4.3.
#include "hotmesh/io/restart_file.hpp"

#include <bit>
#include <cstring>
#include <ostream>

#include <nlohmann/json.hpp>

#include "hotmesh/geometry/input_error.hpp"
#include "hotmesh/io/atomic_file.hpp"

namespace hotmesh::io {
namespace {

static_assert(std::endian::native == std::endian::little, "restart files are little-endian");
constexpr std::string_view kMagic = "HOTMESH-RESTART\n";
constexpr int kVersion = 1;

using nlohmann::json;

void hash_bytes(std::uint64_t& h, const void* data, std::size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 0x100000001b3ull;  // FNV-1a
  }
}

json samples_json(const DeflectionSpec& d) {
  std::vector<double> points, deflections;
  for (std::size_t j = 0; j < d.samples.size(); ++j) {
    points.insert(points.end(), {d.samples.points[j].x, d.samples.points[j].y, d.samples.points[j].z});
    deflections.insert(deflections.end(), {d.samples.deflections[j].x, d.samples.deflections[j].y, d.samples.deflections[j].z});
  }
  return {{"file", d.file.string()},
          {"degree", d.degree},
          {"form", geometry::to_string(d.form)},
          {"faces", d.faces},
          {"frame", static_cast<int>(d.samples.frame)},
          {"source", d.samples.source},
          {"points", points},
          {"deflections", deflections},
          {"ids", d.samples.ids}};
}

DeflectionSpec samples_from_json(const json& j) {
  DeflectionSpec d;
  d.file = j.at("file").get<std::string>();
  d.degree = j.at("degree").get<int>();
  d.form = j.at("form").get<std::string>() == "displacement" ? geometry::DeflectionForm::displacement
                                                             : geometry::DeflectionForm::curve;
  d.faces = j.at("faces").get<std::vector<int>>();
  d.samples.frame = static_cast<geometry::SampleFrame>(j.at("frame").get<int>());
  d.samples.source = j.at("source").get<std::string>();
  const auto points = j.at("points").get<std::vector<double>>();
  const auto deflections = j.at("deflections").get<std::vector<double>>();
  if (points.size() != deflections.size() || points.size() % 3 != 0) throw std::runtime_error("table sizes differ");
  for (std::size_t i = 0; i < points.size(); i += 3) {
    d.samples.points.push_back({points[i], points[i + 1], points[i + 2]});
    d.samples.deflections.push_back({deflections[i], deflections[i + 1], deflections[i + 2]});
  }
  d.samples.ids = j.at("ids").get<std::vector<std::int64_t>>();
  return d;
}

template <class T>
void write_array(std::ostream& out, const std::vector<T>& v) {
  const std::uint64_t n = v.size();
  out.write(reinterpret_cast<const char*>(&n), sizeof n);
  out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
}

/// Reads from a byte buffer, refusing to run past its end.
class Reader {
 public:
  Reader(const std::string& bytes, const std::filesystem::path& path) : bytes_(bytes), path_(path) {}
  void read(void* out, std::size_t size) {
    if (size > bytes_.size() - at_) throw InputError::in(path_.string(), "the restart file is cut short (damaged?)");
    std::memcpy(out, bytes_.data() + at_, size);
    at_ += size;
  }
  template <class T>
  std::vector<T> array(std::uint64_t expected) {
    std::uint64_t n = 0;
    read(&n, sizeof n);
    if (n != expected || n > (bytes_.size() - at_) / sizeof(T)) {
      throw InputError::in(path_.string(), "the restart file is damaged (array sizes do not match)");
    }
    std::vector<T> v(static_cast<std::size_t>(n));
    read(v.data(), v.size() * sizeof(T));
    return v;
  }
  std::size_t at() const { return at_; }
  void skip(std::size_t n) { at_ += n; }

 private:
  const std::string& bytes_;
  const std::filesystem::path& path_;
  std::size_t at_ = 0;
};

}  // namespace

std::uint64_t mesh_fingerprint(const deform::Mesh& mesh) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  hash_bytes(h, &mesh.dimension, sizeof mesh.dimension);
  hash_bytes(h, mesh.points.data(), mesh.points.size() * sizeof(deform::Vec3));
  const auto nodes = mesh.cells.all_nodes();
  hash_bytes(h, nodes.data(), nodes.size() * sizeof(deform::NodeId));
  return h;
}

RestartState restart_state(const Case& c, const deform::Mesh& mesh, const deform::MotionResult& result) {
  RestartState s;
  s.mesh_fingerprint = mesh_fingerprint(mesh);
  s.points = result.points;
  s.sliding = result.sliding_origins;
  s.case_file = c.file.string();
  for (const PatchSpec& p : c.patches) s.patches.push_back({p.name, p.role, p.deflection});
  return s;
}

void write_restart(const std::filesystem::path& path, const RestartState& state) {
  json header{{"format_version", kVersion},
              {"hotmesh_version", HOTMESH_IO_VERSION},
              {"case", state.case_file},
              {"mesh_fingerprint", state.mesh_fingerprint},
              {"nodes", state.points.size()},
              {"sliding_nodes", state.sliding.size()},
              {"patches", json::array()}};
  for (const RestartPatch& p : state.patches) {
    json entry{{"name", p.name}, {"role", deform::to_string(p.role)}};
    if (p.deflection) entry["deflection"] = samples_json(*p.deflection);
    header["patches"].push_back(entry);
  }
  const std::string text = header.dump();
  AtomicFile file(path);
  std::ostream& out = file.stream();
  out.write(kMagic.data(), static_cast<std::streamsize>(kMagic.size()));
  const std::uint64_t length = text.size();
  out.write(reinterpret_cast<const char*>(&length), sizeof length);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  write_array(out, state.points);
  std::vector<deform::NodeId> nodes;
  std::vector<double> parameters;
  for (const auto& o : state.sliding) {
    nodes.push_back(o.node);
    parameters.push_back(o.parameter);
  }
  write_array(out, nodes);
  write_array(out, parameters);
  file.commit();
}

RestartState read_restart(const std::filesystem::path& path, const deform::Mesh& mesh) {
  const std::string bytes = read_file(path);
  if (bytes.compare(0, kMagic.size(), kMagic) != 0) {
    throw InputError::in(path.string(), "not a hotmesh restart file (write one with `hotmesh deform`: restart.hmr)");
  }
  Reader in(bytes, path);
  in.skip(kMagic.size());
  std::uint64_t length = 0;
  in.read(&length, sizeof length);
  if (length > bytes.size() - in.at()) throw InputError::in(path.string(), "the restart file is cut short (damaged?)");
  RestartState s;
  std::uint64_t nodes = 0, sliding = 0;
  try {
    const json header = json::parse(bytes.substr(in.at(), static_cast<std::size_t>(length)));
    in.skip(static_cast<std::size_t>(length));
    if (header.at("format_version").get<int>() != kVersion) {
      throw InputError::in(path.string(), "restart file format " + std::to_string(header.at("format_version").get<int>()) +
                                              " is not the one this hotmesh reads (" + std::to_string(kVersion) + ")");
    }
    s.mesh_fingerprint = header.at("mesh_fingerprint").get<std::uint64_t>();
    s.case_file = header.at("case").get<std::string>();
    nodes = header.at("nodes").get<std::uint64_t>();
    sliding = header.at("sliding_nodes").get<std::uint64_t>();
    for (const json& p : header.at("patches")) {
      RestartPatch patch;
      patch.name = p.at("name").get<std::string>();
      const std::string role = p.at("role").get<std::string>();
      for (int r = 0; r <= static_cast<int>(deform::BoundaryRole::periodic); ++r) {
        if (deform::to_string(static_cast<deform::BoundaryRole>(r)) == role) patch.role = static_cast<deform::BoundaryRole>(r);
      }
      if (p.contains("deflection")) patch.deflection = samples_from_json(p.at("deflection"));
      s.patches.push_back(std::move(patch));
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError::in(path.string(), std::string("the restart file's header is damaged: ") + e.what());
  }
  if (s.mesh_fingerprint != mesh_fingerprint(mesh)) {
    throw InputError::in(path.string(), "this restart file was written for another mesh (or another version of it): "
                                        "a restart must use the same undeformed mesh as the run that wrote it (case " +
                                            s.case_file + ")");
  }
  s.points = in.array<deform::Vec3>(nodes);
  const auto ids = in.array<deform::NodeId>(sliding);
  const auto parameters = in.array<double>(sliding);
  for (std::size_t i = 0; i < ids.size(); ++i) s.sliding.push_back({ids[i], parameters[i]});
  return s;
}

}  // namespace hotmesh::io
