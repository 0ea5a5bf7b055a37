// hotmesh serve: the geometry service behind the HTTP API, free of HTTP. It keeps the CAD
// models clients load (uploaded, or read from --root only) and what they build of them: how
// faces are taken (a surface of revolution or surfaces), meridional curves of faces (eq. 20),
// deflected curves reconstructed from FEM nodes (section 4.2, eq. 21) and deflection fields
// d(t, s) reconstructed on faces of any shape (section 4.2 on B-spline surfaces, issue 23), and
// answers with JSON. Bad requests throw ApiError (status 4xx and what is wrong).
//
// Thread safety: every method may be called from any number of threads at once. The stores
// are guarded by one mutex held only to look up, insert or evict; a CadModel is used by one
// thread at a time (its own mutex); OpenCASCADE's readers and writers are serialised by the
// geometry kernel; curves and surfaces are immutable once built and shared.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "service/cad_check.hpp"
#include "service/json_fields.hpp"

namespace hotmesh::app::serve {

struct ServiceLimits {
  std::size_t max_body_bytes = 64u << 20;  ///< request bodies, uploads and files read from the root
  std::size_t max_nodes = 100'000;         ///< FEM nodes in one table
  std::size_t max_points = 100'000;        ///< points in one projection request
  std::size_t max_samples = 20'000;        ///< samples of a curve in one answer
  std::size_t max_faces = 1'000;           ///< faces named in one request
  std::size_t max_models = 16;             ///< CAD models kept; loading more drops the least recently used
  std::size_t max_curves = 64;             ///< curves kept; likewise
  std::size_t max_curve_bytes = 256u << 20;  ///< memory of the curves kept (about); likewise
  std::size_t max_surfaces = 32;           ///< surfaces (fields on faces) kept; likewise
  std::size_t max_surface_bytes = 256u << 20;  ///< memory of the surfaces kept (about); likewise
  std::size_t max_grid = 200;              ///< sample grid points per direction of a face in one answer
  std::size_t max_grid_points = 200'000;   ///< sample grid points of all faces in one answer
  CadCheck cad_check;                      ///< each CAD file read by a child first (cad_check.hpp)
};

/// A file to send: content and how to label it.
struct Download {
  std::string content;
  std::string content_type;
  std::string filename;
};

class GeometryService {
 public:
  /// Without a root, loading by path is refused (uploads only).
  GeometryService(const std::optional<std::filesystem::path>& root, ServiceLimits limits);
  GeometryService(const GeometryService&) = delete;
  GeometryService& operator=(const GeometryService&) = delete;
  ~GeometryService();

  const ServiceLimits& limits() const;

  Json health() const;
  /// CAD files and tables below the root.
  Json files() const;

  /// {"path": "parts/casing.step", "unit": "mm"}: reads a file below the root.
  Json load_path(const Json& request);
  /// An uploaded CAD file; `filename` gives its format by extension.
  Json load_upload(std::string_view filename, std::string_view content, std::string_view unit);
  Json models() const;
  Json model(std::string_view id) const;
  Json faces(std::string_view id) const;
  void delete_model(std::string_view id);
  /// {"faces": [1, 2], "axis": {...}, "mode": "auto"}: whether the faces are taken as a surface of
  /// revolution ("meridional", with the axis) or as surfaces ("surface", with the reason under
  /// "auto"), as hotmesh deform and check take them (faces_mode.hpp).
  Json faces_mode(std::string_view model_id, const Json& request);
  /// {"faces": [1, 2], "axis": {...}, "samples": 400}: the faces' meridional curve, kept as a curve.
  Json meridional(std::string_view model_id, const Json& request);

  /// {"model": "m1", "faces": [...], "axis": {...}, "csv": "x,y,z,dx,dy,dz\n...", ...}: the
  /// deflected curve reconstructed through the FEM nodes, kept as a curve.
  Json create_curve(const Json& request);
  /// The answer create_curve (or meridional) gave for the curve, as JSON text.
  std::string curve(std::string_view id) const;
  void delete_curve(std::string_view id);
  /// {"points": [[a, b], ...] or [[x, y, z], ...], "lambda": 1}: closest points on stage lambda.
  Json project(std::string_view curve_id, const Json& request) const;
  /// format "step", "iges" or "csv".
  Download download(std::string_view curve_id, std::string_view format) const;

  /// {"model": "m1", "faces": [...], "csv": "x,y,z,dx,dy,dz\n...", "degree": 3, "grid": 24, ...}:
  /// the deflection field d(t, s) of each face through the FEM nodes (as `hotmesh surface`),
  /// kept as a surface; the answer holds the fit, the nodes' (t, s) and residuals, and each
  /// face's grid of S(t, s) and d(t, s).
  Json create_surface(const Json& request);
  /// The answer create_surface gave for the surface, as JSON text.
  std::string surface(std::string_view id) const;
  void delete_surface(std::string_view id);
  /// The deformed faces S + d; format "step" or "iges".
  Download surface_download(std::string_view surface_id, std::string_view format) const;

  struct State;  ///< what the service keeps (service_state.hpp); internal

 private:
  std::unique_ptr<State> state_;
};

}  // namespace hotmesh::app::serve
