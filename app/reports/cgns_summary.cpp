#include "reports/cgns_summary.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace hotmesh::app {
namespace {

nlohmann::json zone_json(const io::CgnsSummary::Zone& z) {
  nlohmann::json j{{"name", z.name}, {"type", z.type}, {"size", z.size}, {"flow_solutions", z.solutions}};
  j["sections"] = nlohmann::json::array();
  for (const auto& s : z.sections) j["sections"].push_back({{"name", s.name}, {"type", s.type}, {"range", {s.first, s.last}}});
  j["bcs"] = nlohmann::json::array();
  for (const auto& b : z.bcs) {
    j["bcs"].push_back({{"name", b.name}, {"type", b.type}, {"location", b.location}, {"point_set", b.point_set},
                        {"family", b.family}, {"points", b.points}});
  }
  j["connections"] = nlohmann::json::array();
  for (const auto& c : z.connections) j["connections"].push_back({{"name", c.name}, {"kind", c.kind}, {"donor", c.donor}});
  return j;
}

std::string zone_text(const nlohmann::json& z) {
  std::string s = fmt::format("  zone {} ({}, size {})\n", z["name"].get<std::string>(), z["type"].get<std::string>(),
                              fmt::join(z["size"].get<std::vector<long long>>(), " "));
  for (const auto& x : z["sections"]) {
    s += fmt::format("    section {:<20} {:<8} elements {}..{}\n", x["name"].get<std::string>(), x["type"].get<std::string>(),
                     x["range"][0].get<long long>(), x["range"][1].get<long long>());
  }
  for (const auto& b : z["bcs"]) {
    const std::string family = b["family"].get<std::string>();
    s += fmt::format("    BC      {:<20} {:<16} {} {} ({} entries){}\n", b["name"].get<std::string>(),
                     b["type"].get<std::string>(), b["location"].get<std::string>(), b["point_set"].get<std::string>(),
                     b["points"].get<long long>(), family.empty() ? "" : ", family " + family);
  }
  for (const auto& c : z["connections"]) {
    s += fmt::format("    connection {} ({}) to zone {}\n", c["name"].get<std::string>(), c["kind"].get<std::string>(),
                     c["donor"].get<std::string>());
  }
  if (z["flow_solutions"].get<int>() > 0) s += fmt::format("    {} flow solution(s)\n", z["flow_solutions"].get<int>());
  return s;
}

}  // namespace

nlohmann::json cgns_summary_json(const io::CgnsSummary& summary) {
  nlohmann::json j{{"file_type", summary.file_type}};
  j["bases"] = nlohmann::json::array();
  for (const auto& b : summary.bases) {
    nlohmann::json base{{"name", b.name}, {"cell_dimension", b.cell_dimension},
                        {"physical_dimension", b.physical_dimension}, {"families", b.families}};
    base["zones"] = nlohmann::json::array();
    for (const auto& z : b.zones) base["zones"].push_back(zone_json(z));
    j["bases"].push_back(std::move(base));
  }
  return j;
}

std::string cgns_summary_text(const nlohmann::json& cgns) {
  std::string s = fmt::format("cgns        {} file, {} base(s)\n", cgns["file_type"].get<std::string>(), cgns["bases"].size());
  for (const auto& b : cgns["bases"]) {
    s += fmt::format("base {} (cell dimension {}, physical dimension {})\n", b["name"].get<std::string>(),
                     b["cell_dimension"].get<int>(), b["physical_dimension"].get<int>());
    for (const auto& z : b["zones"]) s += zone_text(z);
    if (!b["families"].empty()) s += fmt::format("  families {}\n", fmt::join(b["families"].get<std::vector<std::string>>(), ", "));
  }
  return s;
}

}  // namespace hotmesh::app
