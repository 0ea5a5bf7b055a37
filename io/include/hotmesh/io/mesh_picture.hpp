// hotmesh io: pictures of 2D meshes (cells coloured by quality, their edges drawn), for the
// results pages and for users who would rather look than read.
#pragma once

#include <span>

#include "hotmesh/mesh/mesh.hpp"
#include "hotmesh/io/figure.hpp"

namespace hotmesh::io {

struct MeshDrawing {
  Stroke edges{colors::black, 0.6};
  /// Scaled Jacobian per cell; when given, cells are filled with colormap() over
  /// [quality_lo, 1] (inverted cells in dark red) and a colour bar is added.
  std::span<const double> quality;
  double quality_lo = 0.0;
};

/// Draws the cells of a 2D mesh at `points` (x, y) into `figure`.
void draw_mesh(Figure& figure, const mesh::Mesh& mesh, std::span<const geometry::Vec3> points,
               const MeshDrawing& drawing = {});

}  // namespace hotmesh::io
