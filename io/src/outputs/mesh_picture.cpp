// hotmesh io: drawing 2D meshes into a Figure.
#include "hotmesh/io/mesh_picture.hpp"

#include <stdexcept>
#include <vector>

namespace hotmesh::io {

void draw_mesh(Figure& figure, const mesh::Mesh& mesh, std::span<const geometry::Vec3> points,
               const MeshDrawing& drawing) {
  if (mesh.dimension != 2) throw std::invalid_argument("draw_mesh draws 2D meshes");
  const bool filled = !drawing.quality.empty();
  if (filled && drawing.quality.size() != mesh.cell_count()) {
    throw std::invalid_argument("draw_mesh: one quality value per cell expected");
  }
  const double span = 1.0 - drawing.quality_lo;
  std::vector<PlotPoint> corners;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    corners.clear();
    for (mesh::NodeId n : mesh.cells.nodes(c)) {
      const auto& p = points[static_cast<std::size_t>(n)];
      corners.push_back({p.x, p.y});
    }
    if (filled) {
      const double q = drawing.quality[c];
      const Color fill = q <= 0.0 ? Color{0.45, 0.0, 0.0} : colormap((q - drawing.quality_lo) / span);
      figure.polygon(corners, fill, drawing.edges);
    } else {
      figure.polyline(corners, drawing.edges, true);
    }
  }
  if (filled) figure.color_bar("scaled Jacobian", drawing.quality_lo, 1.0);
}

}  // namespace hotmesh::io
