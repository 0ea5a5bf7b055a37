// hotmesh api: a mesh's summary and quality for reports (see mesh_summary.hpp).
#include "hotmesh/api/mesh_summary.hpp"

#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/solver_quality.hpp"

namespace hotmesh::api {

namespace {

/// The mean of a cell's node positions: where the worst cell of a measure is.
geometry::Vec3 cell_place(const mesh::Mesh& mesh, std::span<const geometry::Vec3> points, mesh::CellId c) {
  geometry::Vec3 sum{};
  const auto nodes = mesh.cells.nodes(static_cast<std::size_t>(c));
  for (mesh::NodeId n : nodes) sum += points[static_cast<std::size_t>(n)];
  return sum / static_cast<double>(nodes.size());
}

/// The flow solver's measures of one summary: each maximum with its worst cell (file number
/// and place).
void put_solver_measures(nlohmann::json& j, const mesh::Mesh& mesh, std::span<const geometry::Vec3> points,
                         const mesh::SolverQualitySummary& s) {
  const auto worst = [&](const mesh::WorstCell& w, const char* value = "max", const char* cell = "worst_cell") {
    nlohmann::json m{{value, w.value}};
    if (w.cell >= 0) {
      const geometry::Vec3 at = cell_place(mesh, points, w.cell);
      m[cell] = mesh.cell_id(w.cell);
      m[std::string(cell) + "_at"] = {at.x, at.y, at.z};
    }
    return m;
  };
  nlohmann::json non_orthogonality = worst(s.max_non_orthogonality);
  non_orthogonality["mean"] = s.mean_non_orthogonality;
  non_orthogonality["severe_faces"] = s.severely_non_orthogonal_faces;
  non_orthogonality["internal_faces"] = s.internal_faces;
  non_orthogonality.update(worst(s.max_boundary_non_orthogonality, "max_boundary", "worst_boundary_cell"));
  j["non_orthogonality"] = std::move(non_orthogonality);
  j["skewness"] = worst(s.max_skewness);
  j["volume_ratio"] = worst(s.max_volume_ratio);
  j["aspect_ratio"] = worst(s.max_aspect_ratio);
}

}  // namespace

nlohmann::json quality_json(const mesh::Mesh& mesh, std::span<const geometry::Vec3> points,
                            const mesh::QualitySummary& q, std::span<const double> per_cell,
                            const mesh::SolverQuality& solver) {
  nlohmann::json j;
  j["min_scaled_jacobian"] = q.min_scaled_jacobian;
  j["mean_scaled_jacobian"] = q.mean_scaled_jacobian;
  j["worst_cell"] = q.worst_cell >= 0 ? mesh.cell_id(q.worst_cell) : 0;
  j["inverted_cells"] = q.inverted_cells;
  j["histogram"] = q.histogram;
  put_solver_measures(j, mesh, points, solver.summary);
  // The same per cell type, in the order of mesh::ElementType.
  std::map<mesh::ElementType, std::vector<mesh::CellId>> cells_of;
  for (std::size_t c = 0; c < per_cell.size() && c < mesh.cell_count(); ++c) {
    cells_of[mesh.cells.type(c)].push_back(static_cast<mesh::CellId>(c));
  }
  j["by_type"] = nlohmann::json::object();
  for (const auto& [type, cells] : cells_of) {
    std::vector<double> values(cells.size());
    for (std::size_t i = 0; i < cells.size(); ++i) values[i] = per_cell[static_cast<std::size_t>(cells[i])];
    const mesh::QualitySummary t = mesh::summarize_quality(values);
    nlohmann::json& by_type = j["by_type"][std::string(mesh::name(type))];
    by_type = {{"cells", t.cells},
               {"min_scaled_jacobian", t.min_scaled_jacobian},
               {"mean_scaled_jacobian", t.mean_scaled_jacobian},
               {"worst_cell", mesh.cell_id(cells[static_cast<std::size_t>(t.worst_cell)])},
               {"inverted_cells", t.inverted_cells},
               {"histogram", t.histogram}};
    if (const auto found = solver.by_type.find(type); found != solver.by_type.end()) {
      put_solver_measures(by_type, mesh, points, found->second);
    }
  }
  return j;
}

std::string quality_text(const nlohmann::json& q, const std::string& indent) {
  std::string s = fmt::format("scaled Jacobian min {:.4f} (cell {}), mean {:.4f}; {} inverted cells\n{}",
                              q["min_scaled_jacobian"].get<double>(), q["worst_cell"].get<long long>(),
                              q["mean_scaled_jacobian"].get<double>(), q["inverted_cells"].get<std::size_t>(), indent);
  const auto cell = [](const nlohmann::json& m, const char* key = "worst_cell") {
    return m.contains(key) ? fmt::format(" (cell {})", m[key].get<long long>()) : std::string();
  };
  const auto& o = q["non_orthogonality"];
  s += fmt::format("non-orthogonality max {:.2f} deg{}, average {:.2f} deg, {} faces over {:.0f} deg; at the boundary max {:.2f} deg{}\n{}",
                   o["max"].get<double>(), cell(o), o["mean"].get<double>(), o["severe_faces"].get<std::size_t>(),
                   mesh::kSevereNonOrthogonality, o["max_boundary"].get<double>(), cell(o, "worst_boundary_cell"), indent);
  s += fmt::format("skewness max {:.3f}{}; volume ratio max {:.3g}{}; aspect ratio max {:.3g}{}\n",
                   q["skewness"]["max"].get<double>(), cell(q["skewness"]), q["volume_ratio"]["max"].get<double>(),
                   cell(q["volume_ratio"]), q["aspect_ratio"]["max"].get<double>(), cell(q["aspect_ratio"]));
  return s;
}

nlohmann::json mesh_summary(const io::LoadedMesh& loaded, const std::filesystem::path& file) {
  const mesh::Mesh& mesh = loaded.mesh;
  nlohmann::json j;
  j["file"] = file.string();
  j["dimension"] = mesh.dimension;
  j["nodes"] = mesh.node_count();
  j["cells"] = mesh.cell_count();
  std::map<std::string, std::size_t> by_type;
  for (auto t : mesh.cells.types()) ++by_type[std::string(mesh::name(t))];
  j["cell_types"] = by_type;
  geometry::Vec3 lo = mesh.points.front(), hi = lo;
  for (const auto& p : mesh.points) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  j["bounds"] = {{"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}};
  j["boundary_faces"] = loaded.validation.boundary_faces;
  j["reoriented_cells"] = loaded.validation.reoriented_cells;
  j["patches"] = nlohmann::json::array();
  for (const auto& p : mesh.patches) {
    j["patches"].push_back({{"name", p.name}, {"tag", p.tag}, {"faces", p.faces.size()}, {"nodes", p.nodes.size()}});
  }
  j["cell_groups"] = nlohmann::json::array();
  for (const auto& g : mesh.cell_groups) {
    j["cell_groups"].push_back({{"name", g.name}, {"tag", g.tag}, {"cells", g.cells.size()}});
  }
  j["notes"] = loaded.validation.notes;
  j["quality"] = mesh_quality_json(loaded);
  return j;
}

nlohmann::json mesh_quality_json(const io::LoadedMesh& loaded) {
  const mesh::Mesh& mesh = loaded.mesh;
  const std::vector<double> per_cell = mesh::scaled_jacobians(mesh.cells, mesh.points);
  return quality_json(mesh, mesh.points, mesh::summarize_quality(per_cell), per_cell,
                      mesh::solver_quality(mesh, mesh.points, loaded.layer));
}

std::string mesh_summary_text(const nlohmann::json& j) {
  std::string types;
  for (const auto& [name, count] : j["cell_types"].items()) {
    types += fmt::format("{}{} {}", types.empty() ? "" : ", ", count.get<std::size_t>(), name);
  }
  const auto& lo = j["bounds"]["min"];
  const auto& hi = j["bounds"]["max"];
  std::string s;
  s += fmt::format("mesh        {}\n", j["file"].get<std::string>());
  s += fmt::format("dimension   {}D\n", j["dimension"].get<int>());
  s += fmt::format("nodes       {}\n", j["nodes"].get<std::size_t>());
  s += fmt::format("cells       {} ({})\n", j["cells"].get<std::size_t>(), types);
  s += fmt::format("bounds      x [{:.6g}, {:.6g}]  y [{:.6g}, {:.6g}]  z [{:.6g}, {:.6g}]\n", lo[0].get<double>(),
                   hi[0].get<double>(), lo[1].get<double>(), hi[1].get<double>(), lo[2].get<double>(),
                   hi[2].get<double>());
  s += fmt::format("boundary    {} faces in {} patches\n", j["boundary_faces"].get<std::size_t>(), j["patches"].size());
  std::size_t width = 5;
  for (const auto& p : j["patches"]) width = std::max(width, p["name"].get<std::string>().size());
  s += fmt::format("  {:<{}}  {:>5}  {:>8}  {:>8}\n", "patch", width, "tag", "faces", "nodes");
  for (const auto& p : j["patches"]) {
    s += fmt::format("  {:<{}}  {:>5}  {:>8}  {:>8}\n", p["name"].get<std::string>(), width, p["tag"].get<int>(),
                     p["faces"].get<std::size_t>(), p["nodes"].get<std::size_t>());
  }
  for (const auto& g : j["cell_groups"]) {
    s += fmt::format("cell group  {} (tag {}): {} cells\n", g["name"].get<std::string>(), g["tag"].get<int>(),
                     g["cells"].get<std::size_t>());
  }
  const auto& q = j["quality"];
  s += "quality     " + quality_text(q, "            ");
  const auto& h = q["histogram"];
  s += "  scaled Jacobian   <=0";
  for (int k = 1; k <= 10; ++k) s += fmt::format(" {:>7}", fmt::format("<={:.1f}", k / 10.0));
  s += "\n  cells           ";
  for (std::size_t k = 0; k <= 10; ++k) s += fmt::format(" {:>7}", h[k].get<std::size_t>());
  s += "\n";
  for (const auto& note : j["notes"]) s += fmt::format("note        {}\n", note.get<std::string>());
  return s;
}

}  // namespace hotmesh::api
