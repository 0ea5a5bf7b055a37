// hotmesh setup: section 4.2 on CAD faces from what a user gives (see face_fit.hpp).
#include "hotmesh/setup/face_fit.hpp"

#include <algorithm>
#include <utility>

#include "hotmesh/core/input_error.hpp"

namespace hotmesh::setup {

SurfaceRun cad_faces_of(const geometry::CadModel& model, std::span<const int> ids) {
  SurfaceRun run;
  for (auto it = ids.begin(); it != ids.end(); ++it) {
    if (std::find(ids.begin(), it, *it) != it) {
      throw InputError::in(model.path().string(), "face " + std::to_string(*it) + " is given twice");
    }
    run.info.push_back(model.face(*it));
    run.faces.push_back(model.cad_face(*it));
  }
  run.unit = model.unit();
  run.cad = model.path().string();
  return run;
}

void fit_deflections(SurfaceRun& run, geometry::DeflectionSamples samples, const geometry::ReconstructionOptions& options) {
  run.fit = geometry::reconstruct_on_faces(run.faces, samples, options);
  run.samples = std::move(samples);
}

SurfaceRun fit_on_cad_faces(const geometry::CadModel& model, std::span<const int> ids,
                            geometry::DeflectionSamples samples, const geometry::ReconstructionOptions& options) {
  SurfaceRun run = cad_faces_of(model, ids);
  fit_deflections(run, std::move(samples), options);
  return run;
}

}  // namespace hotmesh::setup
