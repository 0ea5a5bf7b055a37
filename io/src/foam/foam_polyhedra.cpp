// hotmesh io: OpenFOAM's polyhedra as pyramids and tetrahedra about their centres (see
// foam_polyhedra.hpp).
#include "foam/foam_polyhedra.hpp"

#include <algorithm>
#include <array>
#include <span>

#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/solver_quality.hpp"

namespace hotmesh::io::foam {
namespace {

using geometry::Vec3;
using mesh::NodeId;

/// The points of face f, in the file's order.
std::span<const std::int64_t> face_points(const PolyMesh& mesh, std::size_t f) {
  const auto begin = static_cast<std::size_t>(mesh.faces.offsets[f]);
  const auto end = static_cast<std::size_t>(mesh.faces.offsets[f + 1]);
  return {mesh.faces.nodes.data() + begin, end - begin};
}

std::vector<Vec3> coordinates(const PolyMesh& mesh, std::span<const std::int64_t> points) {
  std::vector<Vec3> out;
  out.reserve(points.size());
  for (const std::int64_t p : points) out.push_back(mesh.points[static_cast<std::size_t>(p)]);
  return out;
}

/// True if the element's corner Jacobians are all positive.
bool positive(mesh::ElementType type, std::span<const Vec3> corners) {
  mesh::ElementPoints e;
  e.count = static_cast<int>(corners.size());
  std::copy(corners.begin(), corners.end(), e.p.begin());
  return mesh::scaled_jacobian(type, e) > 0.0;
}

/// Decides which cells are cut into pieces and which faces get a centre point, then builds the
/// pieces.
class PieceBuilder {
 public:
  PieceBuilder(const PolyMesh& mesh, const CellFaces& cells, VolumeElements& out)
      : mesh_(mesh), cells_(cells), out_(out), centre_(mesh.cell_count, -1) {
    out_.face_centre.assign(mesh_.faces.size(), -1);
  }

  /// Cuts the polyhedra, and the cells of a standard type that are not that element with
  /// positive corners (a snapped hexahedron with a concave corner, which OpenFOAM takes);
  /// gives a centre point to every face of a cut cell with more than four points, and to a quad
  /// on which a cut cell's pyramid would not be positive, and cuts the cell across such a quad
  /// too (so the pieces on both sides share its triangles).
  void decide(const std::vector<FoamCell>& elements) {
    for (std::size_t c = 0; c < elements.size(); ++c) {
      const FoamCell& e = elements[c];
      if (!e.polyhedron) {
        std::vector<Vec3> corners;
        for (int k = 0; k < mesh::node_count(e.type); ++k) corners.push_back(mesh_.points[static_cast<std::size_t>(e.nodes[static_cast<std::size_t>(k)])]);
        if (positive(e.type, corners)) continue;
      }
      cut(c);
    }
    for (bool changed = true; changed;) {
      changed = false;
      for (std::size_t f = 0; f < mesh_.faces.size(); ++f) changed = centre_face_if_needed(f) || changed;
    }
  }

  bool is_cut(std::size_t c) const { return centre_[c] >= 0; }

  /// Cut cell c's faces (outward) into out_.polyhedra and its pieces: the first into `first`,
  /// the others appended to `rest`.
  void add_pieces(std::size_t c, mesh::ElementList& first, mesh::ElementList& rest) {
    mesh::Polyhedra& p = out_.polyhedra;
    p.cells.push_back(static_cast<mesh::CellId>(c));
    const auto centre = static_cast<NodeId>(centre_[c]);
    bool placed = false;
    const auto add = [&](mesh::ElementType type, std::initializer_list<NodeId> nodes) {
      if (!placed) {
        first.add(type, nodes);
        placed = true;
        return;
      }
      rest.add(type, nodes);
      p.piece_of.push_back(static_cast<mesh::CellId>(c));
    };
    for (auto i = static_cast<std::size_t>(cells_.offsets[c]); i < static_cast<std::size_t>(cells_.offsets[c + 1]); ++i) {
      const auto file_face = static_cast<std::size_t>(cells_.faces[i]);
      const auto points = face_points(mesh_, file_face);
      const std::size_t n = points.size();
      const std::size_t begin = p.face_nodes.size();
      for (std::size_t k = 0; k < n; ++k) p.face_nodes.push_back(static_cast<NodeId>(points[cells_.owned[i] ? k : n - 1 - k]));
      p.face_offsets.push_back(static_cast<std::int64_t>(p.face_nodes.size()));
      const std::span<const NodeId> f(p.face_nodes.data() + begin, n);
      // Each piece stands on an outward face with its apex inside: its base reversed.
      if (n == 3) {
        add(mesh::ElementType::tet4, {f[0], f[2], f[1], centre});
      } else if (out_.face_centre[file_face] < 0) {
        add(mesh::ElementType::pyramid5, {f[0], f[3], f[2], f[1], centre});
      } else {
        const auto middle = static_cast<NodeId>(out_.face_centre[file_face]);
        for (std::size_t k = 0; k < n; ++k) add(mesh::ElementType::tet4, {f[k], middle, f[(k + 1) % n], centre});
      }
    }
    p.faces.push_back(static_cast<std::int64_t>(p.face_offsets.size()) - 1);
  }

 private:
  /// The outward points of face i of the cell list (cells_.faces[i]).
  std::vector<Vec3> outward(std::size_t i) const {
    std::vector<Vec3> points = coordinates(mesh_, face_points(mesh_, static_cast<std::size_t>(cells_.faces[i])));
    if (!cells_.owned[i]) std::reverse(points.begin(), points.end());
    return points;
  }

  /// Marks cell c as cut, with a point at its centre.
  void cut(std::size_t c) {
    std::vector<mesh::FaceGeometry> geometry;
    for (auto i = static_cast<std::size_t>(cells_.offsets[c]); i < static_cast<std::size_t>(cells_.offsets[c + 1]); ++i) {
      geometry.push_back(mesh::face_geometry(outward(i)));
    }
    centre_[c] = add_point(mesh::cell_centre(geometry).centre);
  }

  /// True if the pyramid on quad f (outward from cut cell c) with its apex at c's centre has
  /// positive corners.
  bool pyramid_fits(std::size_t f, std::size_t c) const {
    std::vector<Vec3> q = coordinates(mesh_, face_points(mesh_, f));
    if (static_cast<std::size_t>(mesh_.owner[f]) != c) std::reverse(q.begin(), q.end());
    const std::array<Vec3, 5> pyramid{q[0], q[3], q[2], q[1], out_.added_points[static_cast<std::size_t>(centre_[c]) - mesh_.points.size()]};
    return positive(mesh::ElementType::pyramid5, pyramid);
  }

  /// Gives face f a centre point if a cut cell on it needs one (cutting the other cell on it);
  /// true if it did.
  bool centre_face_if_needed(std::size_t f) {
    const auto points = face_points(mesh_, f);
    if (points.size() < 4 || out_.face_centre[f] >= 0) return false;
    const auto owner = static_cast<std::size_t>(mesh_.owner[f]);
    const bool inside = f < mesh_.neighbour.size();
    const std::size_t neighbour = inside ? static_cast<std::size_t>(mesh_.neighbour[f]) : owner;
    const bool needed = points.size() > 4 ? is_cut(owner) || is_cut(neighbour)
                                          : (is_cut(owner) && !pyramid_fits(f, owner)) || (is_cut(neighbour) && !pyramid_fits(f, neighbour));
    if (!needed) return false;
    out_.face_centre[f] = add_point(mesh::face_geometry(coordinates(mesh_, points)).centre);
    for (const std::size_t c : {owner, neighbour}) {
      if (!is_cut(c)) cut(c);
    }
    return true;
  }

  std::int64_t add_point(const Vec3& p) {
    out_.added_points.push_back(p);
    return static_cast<std::int64_t>(mesh_.points.size() + out_.added_points.size() - 1);
  }

  const PolyMesh& mesh_;
  const CellFaces& cells_;
  VolumeElements& out_;
  std::vector<std::int64_t> centre_;  ///< per cell, its centre point if it is cut, else -1
};

}  // namespace

VolumeElements volume_elements(const PolyMesh& mesh, const CellFaces& cells, const std::vector<FoamCell>& elements) {
  VolumeElements out;
  PieceBuilder builder(mesh, cells, out);
  builder.decide(elements);
  mesh::ElementList rest;
  out.cells.reserve(elements.size(), 8 * elements.size());
  for (std::size_t c = 0; c < elements.size(); ++c) {
    const FoamCell& e = elements[c];
    if (builder.is_cut(c)) {
      builder.add_pieces(c, out.cells, rest);
      continue;
    }
    std::array<NodeId, 8> nodes{};
    std::transform(e.nodes.begin(), e.nodes.end(), nodes.begin(), [](std::int64_t p) { return static_cast<NodeId>(p); });
    out.cells.add(e.type, std::span<const NodeId>(nodes.data(), static_cast<std::size_t>(mesh::node_count(e.type))));
  }
  for (std::size_t i = 0; i < rest.size(); ++i) out.cells.add(rest.type(i), rest.nodes(i));
  if (!out.polyhedra.empty()) {
    out.polyhedra.file_points = mesh.points.size();
    out.polyhedra.file_cells = elements.size();
  }
  return out;
}

}  // namespace hotmesh::io::foam
