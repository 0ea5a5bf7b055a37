// hotmesh api: the motion as ParaView time series, for a user to scrub through it.
//   deformed.pvd  the mesh after every increment: series/mesh_NNNN.vtu (scaled Jacobian,
//                 inverted flag, patch and displacement from the undeformed mesh)
//   walls.pvd     the walls its patches follow at the same stages: series/walls_NNNN.vtp
// The time of a step is the increment: 0 the start, k after increment k (k - 1/2 after the
// first half of a halved increment), N + 1 after the corner pass.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "hotmesh/deform/mesh_motion.hpp"
#include "hotmesh/mesh/mesh.hpp"
#include "hotmesh/mesh/solver_quality.hpp"

namespace hotmesh::api {

class SeriesWriter {
 public:
  /// The series of a run of `increments` increments in `folder`. A resumed run (`resumed_time`
  /// >= 0) keeps the steps of the interrupted run up to that time, as its deformed.pvd lists
  /// them; a new run starts empty.
  SeriesWriter(std::filesystem::path folder, const mesh::Mesh& mesh, const mesh::Extrusion& layer,
               std::span<const deform::PatchMotion> motions, double resumed_time = -1.0);

  /// Writes one step: the mesh at `points`, the walls at stage `lambda`, and both .pvd files
  /// listing every step so far (each file atomically, so an interrupted run leaves a series
  /// ParaView reads).
  void add(double time, double lambda, std::span<const geometry::Vec3> points);

  /// The files a run with a series writes in its output folder (besides the series/ folder).
  static std::vector<std::string> output_names() { return {"deformed.pvd", "walls.pvd"}; }

 private:
  struct Step {
    double time;
    std::string mesh_file;   ///< relative to the output folder
    std::string walls_file;
  };
  void write_collections() const;

  std::filesystem::path folder_;
  const mesh::Mesh& mesh_;
  mesh::Extrusion layer_;  ///< a 2D mesh's layer of cells, for the flow solver's measures
  std::span<const deform::PatchMotion> motions_;
  std::vector<Step> steps_;
};

}  // namespace hotmesh::api
