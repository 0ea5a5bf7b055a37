// hotmesh io: restart files (restart.hmr), section 4.3.
#include "hotmesh/io/restart_file.hpp"

#include <ostream>

#include <nlohmann/json.hpp>

#include "state/binary_file.hpp"
#include "header_integers.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/geometry/reconstruction.hpp"
#include "hotmesh/io/atomic_file.hpp"

namespace hotmesh::io {
namespace {

constexpr std::string_view kMagic = "HOTMESH-RESTART\n";
/// Version 2 gives each sliding node's material parameter its (t, s) and face, where version 1
/// held t alone; both are read.
constexpr int kVersion = 2;

using nlohmann::json;
using detail::hash_bytes;
using detail::write_array;

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
          {"edges", d.edges},
          {"frame", static_cast<int>(d.samples.frame)},
          {"source", d.samples.source},
          {"points", points},
          {"deflections", deflections},
          {"ids", d.samples.ids}};
}

DeflectionSpec samples_from_json(const json& j) {
  using detail::integer_value;
  DeflectionSpec d;
  d.file = j.at("file").get<std::string>();
  d.degree = integer_value<int>(j.at("degree"));
  if (d.degree < 1 || d.degree > geometry::kMaxReconstructionDegree) {
    throw std::out_of_range("degree " + std::to_string(d.degree) + " is not 1 to " +
                            std::to_string(geometry::kMaxReconstructionDegree));
  }
  const auto form = j.at("form").get<std::string>();
  const auto known_form = geometry::kDeflectionFormNames.parse(form);
  if (!known_form) throw std::domain_error("unknown form '" + form + "'");
  d.form = *known_form;
  d.faces = detail::integer_values<int>(j.at("faces"));
  if (j.contains("edges")) d.edges = detail::integer_values<int>(j.at("edges"));  // since 2D walls from CAD
  const int frame = integer_value<int>(j.at("frame"));
  if (frame < 0 || frame > static_cast<int>(geometry::SampleFrame::meridional)) {
    throw std::out_of_range("unknown frame " + std::to_string(frame));
  }
  d.samples.frame = static_cast<geometry::SampleFrame>(frame);
  d.samples.source = j.at("source").get<std::string>();
  const auto points = j.at("points").get<std::vector<double>>();
  const auto deflections = j.at("deflections").get<std::vector<double>>();
  if (points.size() != deflections.size() || points.size() % 3 != 0) throw std::runtime_error("table sizes differ");
  for (std::size_t i = 0; i < points.size(); i += 3) {
    d.samples.points.push_back({points[i], points[i + 1], points[i + 2]});
    d.samples.deflections.push_back({deflections[i], deflections[i + 1], deflections[i + 2]});
  }
  d.samples.ids = detail::integer_values<std::int64_t>(j.at("ids"));
  return d;
}

}  // namespace

std::uint64_t mesh_fingerprint(const mesh::Mesh& mesh) {
  std::uint64_t h = detail::kFnvOffset;
  hash_bytes(h, &mesh.dimension, sizeof mesh.dimension);
  hash_bytes(h, mesh.points.data(), mesh.points.size() * sizeof(geometry::Vec3));
  const auto nodes = mesh.cells.all_nodes();
  hash_bytes(h, nodes.data(), nodes.size() * sizeof(mesh::NodeId));
  return h;
}

RestartState restart_state(const Case& c, const mesh::Mesh& mesh, const deform::MotionResult& result) {
  RestartState s;
  s.mesh_fingerprint = mesh_fingerprint(mesh);
  s.points = result.restart_points.empty() ? result.points : result.restart_points;
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
  AtomicFile file(path);
  std::ostream& out = file.stream();
  detail::write_header(out, kMagic, header.dump());
  write_array(out, state.points);
  std::vector<mesh::NodeId> nodes;
  std::vector<double> t, s;
  std::vector<std::int32_t> faces;
  for (const auto& o : state.sliding) {
    nodes.push_back(o.node);
    t.push_back(o.parameter.t);
    s.push_back(o.parameter.s);
    faces.push_back(o.parameter.face);
  }
  write_array(out, nodes);
  write_array(out, t);
  write_array(out, s);
  write_array(out, faces);
  file.commit();
}

RestartState read_restart(const std::filesystem::path& path, const mesh::Mesh& mesh) {
  const std::string bytes = read_file(path);
  detail::BinaryReader in(bytes, path, "restart file");
  const std::string text = in.header(kMagic, "write one with `hotmesh deform`: restart.hmr");
  RestartState s;
  std::uint64_t nodes = 0, sliding = 0;
  int version = 0;
  try {
    const json header = json::parse(text);
    using detail::integer_value;
    version = integer_value<int>(header.at("format_version"));
    if (version < 1 || version > kVersion) {
      throw InputError::in(path.string(), "restart file format " + std::to_string(version) +
                                              " is not one this hotmesh reads (1 to " + std::to_string(kVersion) + ")");
    }
    s.mesh_fingerprint = integer_value<std::uint64_t>(header.at("mesh_fingerprint"));
    s.case_file = header.at("case").get<std::string>();
    nodes = integer_value<std::uint64_t>(header.at("nodes"));
    sliding = integer_value<std::uint64_t>(header.at("sliding_nodes"));
    for (const json& p : header.at("patches")) {
      RestartPatch patch;
      patch.name = p.at("name").get<std::string>();
      const std::string role = p.at("role").get<std::string>();
      const auto known = deform::kBoundaryRoleNames.parse(role);
      if (!known) throw std::domain_error("patch '" + patch.name + "' has an unknown role '" + role + "'");
      patch.role = *known;
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
  s.points = in.array<geometry::Vec3>(nodes);
  const auto ids = in.array<mesh::NodeId>(sliding);
  const auto t = in.array<double>(sliding);
  const auto on_faces = version >= 2;  // version 1: curve parameters only
  const auto surface_s = on_faces ? in.array<double>(sliding) : std::vector<double>(t.size(), 0.0);
  const auto faces = on_faces ? in.array<std::int32_t>(sliding) : std::vector<std::int32_t>(t.size(), 0);
  for (std::size_t i = 0; i < ids.size(); ++i) s.sliding.push_back({ids[i], {t[i], surface_s[i], faces[i]}});
  return s;
}

}  // namespace hotmesh::io
