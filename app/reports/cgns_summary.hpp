// hotmesh app: what `hotmesh info` shows of a CGNS file beyond the mesh: bases, zones (type,
// sizes), sections, BCs, connections and families (io::describe_cgns).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "hotmesh/io/cgns.hpp"

namespace hotmesh::app {

nlohmann::json cgns_summary_json(const io::CgnsSummary& summary);
/// The "cgns" part of `info --json` as aligned text.
std::string cgns_summary_text(const nlohmann::json& cgns);

}  // namespace hotmesh::app
