// hotmesh io: restart files (restart.hmr). A run that completes writes where it left the
// mesh, the material parameters of its sliding nodes and the deflection tables it followed;
// the next coupling iteration names the file under `restart:` in its case and continues from
// there with new deflections (the paper's section 4.3). The file is binary: a magic line, a
// JSON header (versions, mesh fingerprint, patches and their tables), then the node positions
// and the sliding nodes as little-endian arrays.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "hotmesh/mesh/mesh.hpp"
#include "hotmesh/deform/mesh_motion.hpp"
#include "hotmesh/io/case_file.hpp"

namespace hotmesh::io {

struct RestartPatch {
  std::string name;
  deform::BoundaryRole role = deform::BoundaryRole::fixed;
  std::optional<DeflectionSpec> deflection;  ///< the table the run followed, samples included
};

struct RestartState {
  std::uint64_t mesh_fingerprint = 0;  ///< of the undeformed mesh the run started from
  std::vector<geometry::Vec3> points;    ///< where the run left every node
  std::vector<deform::SlidingOrigin> sliding;
  std::vector<RestartPatch> patches;
  std::string case_file;               ///< for messages
};

/// A hash of a mesh's dimension, coordinates and cells: restart files belong to one mesh.
std::uint64_t mesh_fingerprint(const mesh::Mesh& mesh);

/// The state after a successful run of case `c` on `mesh`.
RestartState restart_state(const Case& c, const mesh::Mesh& mesh, const deform::MotionResult& result);

void write_restart(const std::filesystem::path& path, const RestartState& state);

/// Reads a restart file written for `mesh`. Throws hotmesh::InputError naming the file if it
/// is not a restart file, is damaged, or belongs to another mesh.
RestartState read_restart(const std::filesystem::path& path, const mesh::Mesh& mesh);

}  // namespace hotmesh::io
