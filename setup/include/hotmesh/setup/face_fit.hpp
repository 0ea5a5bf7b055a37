// hotmesh setup: section 4.2 on CAD faces of any shape from what a user gives (issue 23): the
// faces of a CAD file by number, a cartesian table of FEM nodes, and the deflection field d(t, s)
// reconstructed on each face (geometry::reconstruct_on_faces). `hotmesh surface` writes what
// comes of it (surface_outputs.hpp); `hotmesh serve` answers with it (service/service_surfaces.cpp).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/geometry/deflection_samples.hpp"
#include "hotmesh/geometry/surface_shape.hpp"

namespace hotmesh::setup {

/// A reconstruction on CAD faces and what it was made from.
struct SurfaceRun {
  std::vector<geometry::CadFace> faces;  ///< in the order given
  std::vector<geometry::FaceInfo> info;  ///< the same faces as the CAD file lists them
  geometry::FaceDeflections fit;         ///< one field per face; placements of the nodes used
  geometry::DeflectionSamples samples;
  geometry::LengthUnit unit = geometry::LengthUnit::metre;
  std::string cad;
};

/// The faces `ids` of `model` in B-spline form, its unit and file, nothing fitted yet: the part
/// that reads the model (one thread at a time, as CadModel asks). Throws hotmesh::InputError
/// naming the file for a face the model lacks or one given twice.
SurfaceRun cad_faces_of(const geometry::CadModel& model, std::span<const int> ids);

/// The deflection field of each face of `run` through the samples, which the run keeps. Throws
/// as reconstruct_on_faces does for the table (not cartesian, nodes far from the faces, a face
/// without nodes or with too few for the degree).
void fit_deflections(SurfaceRun& run, geometry::DeflectionSamples samples, const geometry::ReconstructionOptions& options);

/// cad_faces_of, then fit_deflections.
SurfaceRun fit_on_cad_faces(const geometry::CadModel& model, std::span<const int> ids,
                            geometry::DeflectionSamples samples, const geometry::ReconstructionOptions& options);

}  // namespace hotmesh::setup
