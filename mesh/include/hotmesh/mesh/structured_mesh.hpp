// hotmesh mesh: structured quad and hex blocks built from coordinate lines, with one patch
// per side. Used by samples, benchmarks and tests to build meshes in code.
#pragma once

#include <array>
#include <span>
#include <string>

#include "hotmesh/mesh/mesh.hpp"

namespace hotmesh::mesh {

/// Quads on the grid xs x ys (strictly increasing coordinates), nodes numbered x fastest.
/// Patches, in order: names[0] at x = xs.front(), names[1] at x = xs.back(),
/// names[2] at y = ys.front(), names[3] at y = ys.back().
Mesh structured_quads(std::span<const double> xs, std::span<const double> ys,
                      const std::array<std::string, 4>& names = {"xmin", "xmax", "ymin", "ymax"});

/// Hexes on the grid xs x ys x zs, nodes numbered x fastest then y then z.
/// Patches, in order: xmin, xmax, ymin, ymax, zmin, zmax (or the names given).
Mesh structured_hexes(std::span<const double> xs, std::span<const double> ys, std::span<const double> zs,
                      const std::array<std::string, 6>& names = {"xmin", "xmax", "ymin", "ymax", "zmin",
                                                                 "zmax"});

/// n + 1 points from a to b, uniform.
std::vector<double> uniform_line(double a, double b, int n);
/// n + 1 points from a to b whose spacing grows by `ratio` from one interval to the next.
std::vector<double> geometric_line(double a, double b, int n, double ratio);
/// n + 1 points from a to b, spacing growing geometrically from `first_spacing` at a
/// (first_spacing < (b - a) / n; the growth ratio is solved for).
std::vector<double> stretched_line(double a, double b, int n, double first_spacing);

}  // namespace hotmesh::mesh
