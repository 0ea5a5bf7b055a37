// hotmesh app: what is made of deflection fields reconstructed on CAD faces, for CAD systems and
// for people: the deformed faces S + d as B-spline faces (STEP, IGES), the FEM nodes with their
// (t, s) and residuals and the deformed faces as VTK PolyData (ParaView), a picture of the
// residuals over each face's (t, s) rectangle (PNG) and a summary of the fit (JSON). `hotmesh
// surface` writes them to a folder.
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "hotmesh/setup/face_fit.hpp"
#include "hotmesh/geometry/cad_export.hpp"
#include "hotmesh/geometry/deformed_face.hpp"
#include "hotmesh/io/figure.hpp"
#include "hotmesh/io/vtu.hpp"

namespace hotmesh::app {

/// The files write_surface_outputs writes.
inline constexpr std::array<const char*, 6> kSurfaceFiles{"deformed.step", "deformed.iges", "nodes.vtp",
                                                          "faces.vtp",     "residuals.png", "summary.json"};

struct SurfaceOutputOptions {
  std::size_t samples = 48;               ///< grid intervals per direction of each face in faces.vtp
  geometry::DeformedFaceOptions deformed;  ///< how rational faces are interpolated for export
};

/// |d(t_j, s_j) - delta_j| of every placement of run.fit, in the same order.
std::vector<double> placement_residuals(const setup::SurfaceRun& run);

/// Each face's S + d as one B-spline (geometry::deformed_face), in the order of run.faces.
std::vector<geometry::DeformedFace> deformed_faces(const setup::SurfaceRun& run, const geometry::DeformedFaceOptions& options);

/// The deformed faces, named "face <id>", in the run's unit.
geometry::CadExport surface_export(const setup::SurfaceRun& run, std::span<const geometry::DeformedFace> deformed);

/// The FEM nodes as vertices at their undeformed positions Q_j: one per placement (a node on an
/// edge two faces share is there twice), then one per node left out. Point arrays: deflection,
/// face (CAD number; 0 for nodes left out), t, s, distance (to the face; to the nearest face for
/// nodes left out), residual (NaN where there is no face, as t and s), rejected (1 for nodes left
/// out), line (in the table) and id (where the table has ids).
io::PolyData node_points(const setup::SurfaceRun& run, std::span<const double> residuals);

/// Each deformed face S + d sampled on a grid of (samples + 1)^2 parameters and cut into
/// triangles (their order gives the normal S_t x S_s). Point arrays: deflection d,
/// deflection_magnitude |d|, face (CAD number), t, s.
io::PolyData face_grids(const setup::SurfaceRun& run, std::size_t samples);

/// One panel per face: its (t, s) rectangle drawn with the face's proportions, the knot lines
/// of d, the FEM nodes coloured by their residual on one scale for all faces, the worst node of
/// each face ringed, and the face's number, node count, method and largest residual above it.
io::Figure residual_picture(const setup::SurfaceRun& run, std::span<const double> residuals);

/// The fit in numbers, as summary.json: inputs, degree, tolerance, nodes (used, rejected with
/// labels), per face its fit and export, max_edge_gap, max_node_distance_to_cad,
/// max_node_residual.
nlohmann::json surface_summary(const setup::SurfaceRun& run, std::span<const geometry::DeformedFace> deformed);

/// Writes kSurfaceFiles into `folder` (which exists), each atomically, after everything has
/// been computed. Returns the summary.
nlohmann::json write_surface_outputs(const std::filesystem::path& folder, const setup::SurfaceRun& run,
                                     const SurfaceOutputOptions& options);

}  // namespace hotmesh::app
