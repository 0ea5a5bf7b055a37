// hotmesh app: the files `hotmesh curve` writes for a reconstructed boundary curve: sampled
// curves (CSV), both curves as B-splines (STEP, IGES), a picture (SVG) and a summary (JSON).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/geometry/reconstruction.hpp"

namespace hotmesh::app {

/// A reconstruction and what it was made from.
struct CurveRun {
  geometry::Reconstruction fit;
  geometry::CurveSamples nodes;
  std::optional<geometry::Axis> axis;  ///< for (r, z) curves; none for 2D (x, y) curves
  geometry::LengthUnit unit = geometry::LengthUnit::metre;
  std::vector<int> faces;               ///< CAD faces along the curve; empty without CAD
  std::string cad;                      ///< CAD file, empty without CAD
};

struct CurveOutputOptions {
  std::size_t samples = 2000;  ///< uniform samples in t, plus every knot
  double amplification = 0.0;  ///< deflection scale in the picture; 0: automatic
};

/// Writes undeformed.csv, deformed.csv, curves.step, curves.igs, plot.svg and summary.json
/// into `folder` (which exists), each atomically. Returns the summary.
std::string write_curve_outputs(const std::filesystem::path& folder, const CurveRun& run,
                                const CurveOutputOptions& options);

}  // namespace hotmesh::app
