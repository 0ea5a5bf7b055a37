#include "mesh_summary.hpp"

#include <algorithm>
#include <map>

#include <fmt/format.h>

#include "hotmesh/mesh/quality.hpp"

namespace hotmesh::app {

nlohmann::json quality_json(const mesh::Mesh& mesh, const mesh::QualitySummary& q, std::span<const double> per_cell) {
  nlohmann::json j;
  j["min_scaled_jacobian"] = q.min_scaled_jacobian;
  j["mean_scaled_jacobian"] = q.mean_scaled_jacobian;
  j["worst_cell"] = q.worst_cell >= 0 ? mesh.cell_id(q.worst_cell) : 0;
  j["inverted_cells"] = q.inverted_cells;
  j["histogram"] = q.histogram;
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
    j["by_type"][std::string(mesh::name(type))] = {{"cells", t.cells},
                                                   {"min_scaled_jacobian", t.min_scaled_jacobian},
                                                   {"mean_scaled_jacobian", t.mean_scaled_jacobian},
                                                   {"worst_cell", mesh.cell_id(cells[static_cast<std::size_t>(t.worst_cell)])},
                                                   {"inverted_cells", t.inverted_cells},
                                                   {"histogram", t.histogram}};
  }
  return j;
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
  const std::vector<double> per_cell = mesh::scaled_jacobians(mesh.cells, mesh.points);
  j["quality"] = quality_json(mesh, mesh::summarize_quality(per_cell), per_cell);
  return j;
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
  s += fmt::format("quality     scaled Jacobian min {:.4f} (cell {}), mean {:.4f}; {} inverted cells\n",
                   q["min_scaled_jacobian"].get<double>(), q["worst_cell"].get<long long>(),
                   q["mean_scaled_jacobian"].get<double>(), q["inverted_cells"].get<std::size_t>());
  const auto& h = q["histogram"];
  s += "  scaled Jacobian   <=0";
  for (int k = 1; k <= 10; ++k) s += fmt::format(" {:>7}", fmt::format("<={:.1f}", k / 10.0));
  s += "\n  cells           ";
  for (std::size_t k = 0; k <= 10; ++k) s += fmt::format(" {:>7}", h[k].get<std::size_t>());
  s += "\n";
  for (const auto& note : j["notes"]) s += fmt::format("note        {}\n", note.get<std::string>());
  return s;
}

}  // namespace hotmesh::app
