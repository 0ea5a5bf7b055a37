// hotmesh api: what a user wants to know about a mesh, as JSON (for `info --json` and the
// report.json of every run) and as text.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include <span>

#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/solver_quality.hpp"
#include "hotmesh/io/mesh_files.hpp"

namespace hotmesh::api {

/// Counts, bounds, patches, cell groups, validation notes and the quality summary.
nlohmann::json mesh_summary(const io::LoadedMesh& loaded, const std::filesystem::path& file);

/// The quality of a mesh with its nodes at `points` as JSON: the scaled Jacobian's summary
/// (mesh::QualitySummary), the measures a flow solver uses (mesh::SolverQuality), each with its
/// worst cell's number and place, and the same per cell type (`per_cell`: the scaled Jacobian
/// of each cell).
nlohmann::json quality_json(const mesh::Mesh& mesh, std::span<const geometry::Vec3> points,
                            const mesh::QualitySummary& quality, std::span<const double> per_cell,
                            const mesh::SolverQuality& solver);

/// quality_json of a mesh as read.
nlohmann::json mesh_quality_json(const io::LoadedMesh& loaded);

/// quality_json's maxima as three lines of text (the scaled Jacobian; non-orthogonality;
/// skewness, volume and aspect ratios), for the terminal; the second and third start with
/// `indent`.
std::string quality_text(const nlohmann::json& quality, const std::string& indent = "");

/// The summary as aligned text for a terminal.
std::string mesh_summary_text(const nlohmann::json& summary);

}  // namespace hotmesh::api
