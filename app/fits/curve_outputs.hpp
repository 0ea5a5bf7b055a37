// hotmesh app: what is made of a reconstructed boundary curve for people and CAD systems:
// sampled curves (CSV), both curves as B-splines (STEP, IGES), a picture (SVG) and a summary of
// the fit (JSON). `hotmesh curve` writes them to a folder; `hotmesh serve` sends them.
#pragma once

#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "hotmesh/setup/curve_fit.hpp"
#include "hotmesh/geometry/cad_export.hpp"

namespace hotmesh::app {

/// The files write_curve_outputs writes.
inline constexpr std::array<const char*, 6> kCurveFiles{"undeformed.csv", "deformed.csv", "curves.step",
                                                        "curves.igs",     "plot.svg",     "summary.json"};

struct CurveOutputOptions {
  std::size_t samples = 2000;  ///< uniform samples in t, plus every knot
  double amplification = 0.0;  ///< deflection scale in the picture; 0: automatic
};

/// `samples` + 1 uniform parameters over the curve plus every piece end (so corners are
/// sampled exactly), sorted, without repeats.
std::vector<double> sample_parameters(const geometry::DeflectedCurve& curve, std::size_t samples);

/// "t,r,z" (meridional) or "t,x,y" rows of the stage-lambda curve at the parameters t.
std::string curve_csv(const geometry::DeflectedCurve& curve, const std::vector<double>& t, double lambda,
                      bool meridional);

/// Both curves ("undeformed", "deformed") as exact B-splines in the plane of the run: the
/// meridional plane of the axis (theta = 0), or the x-y plane for 2D curves.
geometry::CadExport curve_export(const setup::CurveRun& run);

/// A scale that draws the largest deflection at about 10 % of the curve's size (1, 2 or 5
/// times a power of ten, at least 1).
double automatic_amplification(const setup::CurveRun& run);

/// The fit in numbers, as summary.json: nodes, degree, form, ranges, distances, residual,
/// rejected nodes, CAD faces, axis, amplification.
nlohmann::json curve_summary(const setup::CurveRun& run, double amplification);

/// Writes undeformed.csv, deformed.csv, curves.step, curves.igs, plot.svg and summary.json
/// into `folder` (which exists), each atomically. Returns the summary.
std::string write_curve_outputs(const std::filesystem::path& folder, const setup::CurveRun& run,
                                const CurveOutputOptions& options);

}  // namespace hotmesh::app
