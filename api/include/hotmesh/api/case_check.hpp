// hotmesh api: the measurements of `hotmesh check` that the command and the library
// (hotmesh::check) share: a patch's nodes against its reference shape and its faces both
// ways, and the whole check a case file describes (`hotmesh check --case`): every patch that
// follows a boundary against the walls hotmesh deform builds for the case, undeformed for the
// case's own mesh and deflected for a mesh the case was deformed into.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "hotmesh/api/check_references.hpp"
#include "hotmesh/api/check_report.hpp"
#include "hotmesh/mesh/mesh.hpp"

namespace hotmesh::api {

/// The tolerance of a check without one: 1e-6 of the mesh's bounding box diagonal.
double default_tolerance(const mesh::Mesh& mesh);

/// The nodes of `patch` measured against its reference, each node against the nearest part;
/// then its faces, both ways (the wall tolerance, if any, deciding too).
PatchCheck check_patch(const mesh::Patch& patch, const mesh::Mesh& mesh, PatchReference& reference, double tolerance,
                       const std::optional<double>& wall_tolerance);

/// Logs a patch's check in one line.
void log_patch(const PatchCheck& p);

struct CaseCheckOptions {
  std::filesystem::path case_file;
  std::filesystem::path mesh;    ///< the mesh to check; empty: the case's own
  std::filesystem::path output;  ///< where the report goes (refused if it is one of the inputs); empty: none
  double tolerance = 0.0;        ///< 0: default_tolerance
  std::optional<double> wall_tolerance;
};

/// The check a case file describes. `inputs` gets the case's input files and `inputs_known`
/// is set once the case is read. Throws hotmesh::InputError.
CheckResult check_with_case(const CaseCheckOptions& o, std::vector<std::filesystem::path>& inputs, bool& inputs_known);

}  // namespace hotmesh::api
