// hotmesh app: what a user wants to know about a mesh, as JSON (for `info --json` and the
// report.json of every run) and as text.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include <span>

#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/io/mesh_files.hpp"

namespace hotmesh::app {

/// Counts, bounds, patches, cell groups, validation notes and the quality summary.
nlohmann::json mesh_summary(const io::LoadedMesh& loaded, const std::filesystem::path& file);

/// A quality summary (mesh::QualitySummary) as JSON, with the same per cell type from the
/// scaled Jacobian of each cell (`per_cell`).
nlohmann::json quality_json(const mesh::Mesh& mesh, const mesh::QualitySummary& quality, std::span<const double> per_cell);

/// The summary as aligned text for a terminal.
std::string mesh_summary_text(const nlohmann::json& summary);

}  // namespace hotmesh::app
