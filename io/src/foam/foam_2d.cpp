// hotmesh io: one-cell-thick OpenFOAM cases flattened to 2D meshes of quads and triangles
// (see foam_2d.hpp).
//
// The two planes and their 2D frames (origin, u, v; a 2D point (x, y) is origin + x u + y v):
//   empty, normal to z: (x, y) as they are; normal to x: (y, z); normal to y: (z, x) (a cyclic
//     turn of the axes, so the 2D mesh keeps its handedness); each plane's own origin.
//   wedge: u = a, the axis (n_back x n_front, its largest component made positive), through o,
//     the point of the axis nearest the coordinate origin; v = the direction from the axis into
//     the wedge plane. x is then the axial coordinate and y the radius.
#include "foam/foam_2d.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "hotmesh/core/input_error.hpp"

namespace hotmesh::io::foam {
namespace {

using geometry::Vec3;

bool is_planar_type(const std::string& type) { return type == "empty" || type == "wedge"; }

std::span<const std::int64_t> face_points(const PolyMesh& m, std::size_t f) {
  return {m.faces.nodes.data() + m.faces.offsets[f], m.faces.nodes.data() + m.faces.offsets[f + 1]};
}

const Vec3& point(const PolyMesh& m, std::int64_t q) { return m.points[static_cast<std::size_t>(q)]; }

/// Newell's area vector of a face (its normal times its area, right-hand).
Vec3 area_vector(const PolyMesh& m, std::size_t f) {
  const auto p = face_points(m, f);
  Vec3 a;
  for (std::size_t i = 0; i < p.size(); ++i) {
    a = a + geometry::cross(point(m, p[i]), point(m, p[(i + 1) % p.size()]));
  }
  return 0.5 * a;
}

Vec3 unit(const Vec3& v) { return v / geometry::norm(v); }

/// The planar patches' faces split into the two planes; the frames of the planes.
struct Planes {
  std::vector<std::int8_t> plane_of_face;  ///< -1: not on a planar patch
  std::array<PlaneFrame, 2> frames{};
  std::string kind;  ///< "empty" or "wedge"
};

std::vector<const BoundaryPatch*> planar_patches(const PolyMesh& m, const std::string& source) {
  std::vector<const BoundaryPatch*> patches;
  for (const BoundaryPatch& p : m.patches) {
    if (is_planar_type(p.type) && p.face_count > 0) patches.push_back(&p);
  }
  for (const BoundaryPatch* p : patches) {
    if (p->type != patches.front()->type) {
      throw InputError::in(source, fmt::format("patch '{}' is {} and patch '{}' is {}: a 2D case has either empty or "
                                               "wedge front and back patches",
                                               patches.front()->name, patches.front()->type, p->name, p->type));
    }
  }
  return patches;
}

template <class Visit>
void for_faces(const BoundaryPatch& p, Visit visit) {
  for (auto f = static_cast<std::size_t>(p.start_face); f < static_cast<std::size_t>(p.start_face + p.face_count);
       ++f) {
    visit(f);
  }
}

Planes empty_planes(const PolyMesh& m, const std::vector<const BoundaryPatch*>& patches, const std::string& source) {
  const Vec3 first = area_vector(m, static_cast<std::size_t>(patches.front()->start_face));
  int axis = 0;
  for (int k = 1; k < 3; ++k) {
    if (std::abs(first[k]) > std::abs(first[axis])) axis = k;
  }
  const char* axis_name[] = {"x", "y", "z"};
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const BoundaryPatch* p : patches) {
    for_faces(*p, [&](std::size_t f) {
      const Vec3 a = area_vector(m, f);
      if (std::abs(a[axis]) < (1.0 - 1e-6) * geometry::norm(a)) {
        throw InputError::in(source, fmt::format("face {} of the empty patch '{}' is not normal to {} as face {} is: "
                                                 "hotmesh reads 2D cases whose empty planes are normal to x, y or z",
                                                 f, p->name, axis_name[axis], patches.front()->start_face));
      }
      for (const std::int64_t q : face_points(m, f)) {
        lo = std::min(lo, point(m, q)[axis]);
        hi = std::max(hi, point(m, q)[axis]);
      }
    });
  }
  Planes planes;
  planes.kind = "empty";
  planes.plane_of_face.assign(m.faces.size(), -1);
  const double tolerance = 1e-6 * (hi - lo);
  for (const BoundaryPatch* p : patches) {
    for_faces(*p, [&](std::size_t f) {
      int plane = -1;
      for (const std::int64_t q : face_points(m, f)) {
        const double c = point(m, q)[axis];
        const int here = std::abs(c - lo) <= tolerance ? 0 : std::abs(c - hi) <= tolerance ? 1 : -1;
        if (here < 0 || (plane >= 0 && here != plane)) {
          throw InputError::in(source, fmt::format("face {} of the empty patch '{}' is not in the back ({} = {}) or "
                                                   "front ({} = {}) plane: the case is not one cell thick",
                                                   f, p->name, axis_name[axis], lo, axis_name[axis], hi));
        }
        plane = here;
      }
      planes.plane_of_face[f] = static_cast<std::int8_t>(plane);
    });
  }
  const Vec3 e[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const Vec3 u = e[(axis + 1) % 3], v = e[(axis + 2) % 3];
  planes.frames = {PlaneFrame{lo * e[axis], u, v}, PlaneFrame{hi * e[axis], u, v}};
  return planes;
}

/// A wedge patch's plane: unit normal and centroid of its points; checked to be flat.
struct WedgePlane {
  Vec3 normal, centroid;
};

WedgePlane wedge_plane(const PolyMesh& m, const BoundaryPatch& p, const std::string& source) {
  Vec3 area, sum;
  std::size_t count = 0;
  double extent = 0.0;
  for_faces(p, [&](std::size_t f) {
    area = area + area_vector(m, f);
    for (const std::int64_t q : face_points(m, f)) {
      sum = sum + point(m, q);
      ++count;
    }
  });
  WedgePlane plane{unit(area), sum / static_cast<double>(count)};
  for_faces(p, [&](std::size_t f) {
    for (const std::int64_t q : face_points(m, f)) {
      extent = std::max(extent, geometry::distance(point(m, q), plane.centroid));
    }
  });
  for_faces(p, [&](std::size_t f) {
    for (const std::int64_t q : face_points(m, f)) {
      if (std::abs(geometry::dot(point(m, q) - plane.centroid, plane.normal)) > 1e-6 * extent) {
        throw InputError::in(source,
                             fmt::format("the wedge patch '{}' is not planar (point {} is off its plane)", p.name, q));
      }
    }
  });
  return plane;
}

Planes wedge_planes(const PolyMesh& m, const std::vector<const BoundaryPatch*>& patches, const std::string& source) {
  if (patches.size() != 2) {
    throw InputError::in(source, fmt::format("a wedge case needs two wedge patches with faces (back and front), this "
                                             "one has {}",
                                             patches.size()));
  }
  const WedgePlane back = wedge_plane(m, *patches[0], source), front = wedge_plane(m, *patches[1], source);
  Vec3 axis = geometry::cross(back.normal, front.normal);
  if (geometry::norm(axis) < 1e-8) {
    throw InputError::in(source, fmt::format("the wedge patches '{}' and '{}' are parallel: they must meet at the axis",
                                             patches[0]->name, patches[1]->name));
  }
  axis = unit(axis);
  int largest = 0;
  for (int k = 1; k < 3; ++k) {
    if (std::abs(axis[k]) > std::abs(axis[largest])) largest = k;
  }
  if (axis[largest] < 0) axis = -axis;
  // The point of the axis nearest the origin: o = alpha n_b + beta n_f on both planes.
  const double d_back = geometry::dot(back.normal, back.centroid),
               d_front = geometry::dot(front.normal, front.centroid);
  const double c = geometry::dot(back.normal, front.normal), det = 1.0 - c * c;
  const Vec3 origin = ((d_back - c * d_front) / det) * back.normal + ((d_front - c * d_back) / det) * front.normal;
  const auto radial = [&](const WedgePlane& p) {
    const Vec3 r = p.centroid - origin;
    return unit(r - geometry::dot(r, axis) * axis);
  };
  Planes planes;
  planes.kind = "wedge";
  planes.frames = {PlaneFrame{origin, axis, radial(back)}, PlaneFrame{origin, axis, radial(front)}};
  planes.plane_of_face.assign(m.faces.size(), -1);
  for (std::size_t i = 0; i < 2; ++i) {
    for_faces(*patches[i], [&](std::size_t f) { planes.plane_of_face[f] = static_cast<std::int8_t>(i); });
  }
  return planes;
}

/// Each cell's face on the back plane, checked: one face on each plane per cell.
std::vector<std::int64_t> back_faces(const PolyMesh& m, const CellFaces& cells, const Planes& planes,
                                     const std::string& source) {
  std::vector<std::int64_t> back(m.cell_count, -1);
  for (std::size_t c = 0; c < m.cell_count; ++c) {
    int on_back = 0, on_front = 0;
    for (auto i = cells.offsets[c]; i < cells.offsets[c + 1]; ++i) {
      const auto f = cells.faces[static_cast<std::size_t>(i)];
      const int plane = planes.plane_of_face[static_cast<std::size_t>(f)];
      if (plane == 0) back[c] = f;
      on_back += plane == 0;
      on_front += plane == 1;
    }
    if (on_back != 1 || on_front != 1) {
      throw InputError::in(source, fmt::format("cell {} has {} faces on the back and {} on the front {} plane (one on "
                                               "each in a one-cell-thick 2D case)",
                                               c, on_back, on_front, planes.kind));
    }
  }
  return back;
}

/// A cell of a one-cell-thick case as a column between the planes: its back face's points
/// and, for each, the front point a side edge of the cell joins it to (the point itself for
/// a point on the axis, where a wedge case's cells collapse).
struct Column {
  std::size_t count = 0;  ///< 3 (a prism) or 4 (a hexahedron, or a cell collapsed on the axis)
  std::array<std::int64_t, 4> back{};
  std::array<std::int64_t, 4> front{};
};

/// Each cell's column. Throws hotmesh::InputError naming the first cell that is none (a back
/// point joined to no front point or to two, front points other than the front face's) and
/// how many there are.
std::vector<Column> columns(const PolyMesh& m, const CellFaces& cells, const std::vector<std::int64_t>& back_face,
                            const Planes& planes, const std::string& source) {
  std::vector<Column> out(m.cell_count);
  std::size_t others = 0;
  std::string first;
  std::vector<std::array<std::int64_t, 2>> side_edges;  // of one cell, reused
  for (std::size_t c = 0; c < m.cell_count; ++c) {
    const auto back = face_points(m, static_cast<std::size_t>(back_face[c]));
    std::span<const std::int64_t> front;
    side_edges.clear();
    for (auto i = cells.offsets[c]; i < cells.offsets[c + 1]; ++i) {
      const auto f = static_cast<std::size_t>(cells.faces[static_cast<std::size_t>(i)]);
      const auto points = face_points(m, f);
      if (planes.plane_of_face[f] == 1) front = points;
      if (planes.plane_of_face[f] >= 0) continue;
      for (std::size_t k = 0; k < points.size(); ++k) side_edges.push_back({points[k], points[(k + 1) % points.size()]});
    }
    const auto in = [](std::span<const std::int64_t> face, std::int64_t q) {
      return std::find(face.begin(), face.end(), q) != face.end();
    };
    Column column;
    column.count = back.size();
    bool ok = back.size() == 3 || back.size() == 4;
    for (std::size_t k = 0; ok && k < back.size(); ++k) {
      column.back[k] = back[k];
      std::int64_t partner = in(front, back[k]) ? back[k] : -1;  // on the axis: on both planes
      for (const auto& [a, b] : side_edges) {
        if (partner == back[k]) break;
        const std::int64_t other = a == back[k] ? b : (b == back[k] ? a : -1);
        if (other < 0 || in(back, other)) continue;
        ok = ok && (partner < 0 || partner == other) && in(front, other);
        partner = other;
      }
      ok = ok && partner >= 0;
      column.front[k] = partner;
    }
    for (std::size_t k = 0; ok && k < front.size(); ++k) {
      ok = std::find(column.front.begin(), column.front.begin() + static_cast<std::ptrdiff_t>(column.count), front[k]) !=
           column.front.begin() + static_cast<std::ptrdiff_t>(column.count);
    }
    if (ok) {
      out[c] = column;
    } else if (others++ == 0) {
      first = fmt::format("cell {} (back face of {} points, front face of {}) is not a prism or hexahedron standing on "
                          "the back plane",
                          c, back.size(), front.size());
    }
  }
  if (others > 0) {
    throw InputError::in(source, fmt::format("{}; a one-cell-thick (2D) case has cells that join each back point to one "
                                             "front point (quadrilaterals and triangles in 2D), and {} of the {} cells do "
                                             "not",
                                             first, others, m.cell_count));
  }
  return out;
}

/// Each point's plane and the back point it is joined to (itself for a back point).
struct Pairing {
  std::vector<std::int8_t> plane;
  std::vector<std::int64_t> back_point;
};

Pairing pair_points(const PolyMesh& m, const std::vector<Column>& cells, const std::string& source) {
  Pairing p{std::vector<std::int8_t>(m.points.size(), -1), std::vector<std::int64_t>(m.points.size(), -1)};
  const auto mark = [&](std::int64_t point, int plane, std::int64_t back, std::size_t cell) {
    const auto i = static_cast<std::size_t>(point);
    if ((p.plane[i] >= 0 && p.plane[i] != plane) || (p.back_point[i] >= 0 && p.back_point[i] != back)) {
      throw InputError::in(source, fmt::format("point {} (in cell {}) is not where a one-cell-thick 2D case has it: it "
                                               "is on both planes or joined to two back points",
                                               point, cell));
    }
    p.plane[i] = static_cast<std::int8_t>(plane);
    p.back_point[i] = back;
  };
  for (std::size_t c = 0; c < cells.size(); ++c) {
    for (std::size_t i = 0; i < cells[c].count; ++i) {
      mark(cells[c].back[i], 0, cells[c].back[i], c);
      if (cells[c].front[i] != cells[c].back[i]) mark(cells[c].front[i], 1, cells[c].back[i], c);
    }
  }
  const auto unused = std::find(p.plane.begin(), p.plane.end(), std::int8_t{-1});
  if (unused != p.plane.end()) {
    throw InputError::in(source, fmt::format("point {} is in no cell", unused - p.plane.begin()));
  }
  return p;
}

double signed_area(std::span<const Vec3> q) {
  double a = 0.0;
  for (std::size_t i = 0; i < q.size(); ++i) a += q[i].x * q[(i + 1) % q.size()].y - q[(i + 1) % q.size()].x * q[i].y;
  return 0.5 * a;
}

/// The 2D edge of a side face: its two back points, in the order the owner's cell runs.
std::array<mesh::NodeId, 2> side_edge(const PolyMesh& m, const Pairing& pairing, const PointMap& map,
                                      const mesh::Mesh& flat, std::size_t f, const std::string& patch,
                                      const std::string& source) {
  std::vector<mesh::NodeId> ends;
  for (const std::int64_t q : face_points(m, f)) {
    if (pairing.plane[static_cast<std::size_t>(q)] == 0) ends.push_back(map.node[static_cast<std::size_t>(q)]);
  }
  if (ends.size() != 2) {
    throw InputError::in(source, fmt::format("face {} of patch '{}' has {} points on the back plane (a side face of a "
                                             "one-cell-thick case has 2)",
                                             f, patch, ends.size()));
  }
  const auto cell = flat.cells.nodes(static_cast<std::size_t>(m.owner[f]));
  for (std::size_t i = 0; i < cell.size(); ++i) {
    if (cell[i] == ends[1] && cell[(i + 1) % cell.size()] == ends[0]) return {ends[1], ends[0]};
  }
  return {ends[0], ends[1]};
}

/// The back plane's points as the 2D nodes (in OpenFOAM's order, ids = labels + 1); each
/// front point mapped to the node of its back point.
void add_back_points(const PolyMesh& m, const Pairing& pairing, FlatMesh& flat) {
  const PlaneFrame& frame = flat.map.frames[0];
  flat.map.node.assign(m.points.size(), -1);
  for (std::size_t q = 0; q < m.points.size(); ++q) {
    if (pairing.plane[q] != 0) continue;
    flat.map.node[q] = static_cast<mesh::NodeId>(flat.mesh.points.size());
    const Vec3 r = m.points[q] - frame.origin;
    flat.mesh.points.push_back({geometry::dot(r, frame.u), geometry::dot(r, frame.v), 0.0});
    flat.mesh.node_ids.push_back(static_cast<std::int64_t>(q) + 1);
  }
  for (std::size_t q = 0; q < m.points.size(); ++q) {
    if (pairing.plane[q] == 1) flat.map.node[q] = flat.map.node[static_cast<std::size_t>(pairing.back_point[q])];
  }
}

/// Each cell's back face as a quad or a triangle, counter-clockwise in the 2D plane.
void add_cells(const std::vector<Column>& columns, FlatMesh& flat) {
  flat.mesh.cells.reserve(columns.size(), 4 * columns.size());
  for (const Column& column : columns) {
    std::array<mesh::NodeId, 4> nodes{};
    std::array<Vec3, 4> corners{};
    for (std::size_t i = 0; i < column.count; ++i) {
      nodes[i] = flat.map.node[static_cast<std::size_t>(column.back[i])];
      corners[i] = flat.mesh.points[static_cast<std::size_t>(nodes[i])];
    }
    if (signed_area({corners.data(), column.count}) < 0) std::reverse(nodes.begin() + 1, nodes.begin() + static_cast<std::ptrdiff_t>(column.count));
    flat.mesh.cells.add(column.count == 3 ? mesh::ElementType::tri3 : mesh::ElementType::quad4,
                        std::span<const mesh::NodeId>(nodes.data(), column.count));
  }
}

/// The patches other than empty/wedge, their faces as the edges they have on the back plane.
void add_side_patches(const PolyMesh& m, const Pairing& pairing, FlatMesh& flat, const std::string& source) {
  int tag = 0;
  for (const BoundaryPatch& p : m.patches) {
    ++tag;
    if (p.face_count == 0 || is_planar_type(p.type)) continue;
    mesh::Patch patch{.name = p.name, .tag = tag, .faces = {}, .nodes = {}};
    for_faces(p, [&](std::size_t f) {
      patch.faces.add(mesh::ElementType::line2, side_edge(m, pairing, flat.map, flat.mesh, f, p.name, source));
    });
    flat.mesh.patches.push_back(std::move(patch));
  }
}

/// A wedge case's cells that reach the axis have an edge on it (their face there collapsed, so
/// OpenFOAM has no face for it): those edges as a patch, named as the case's empty patch
/// without faces (blockMesh's "axis") or "axis", for the case file to give a role (slip).
void add_axis_patch(const PolyMesh& m, const std::vector<Column>& columns, FlatMesh& flat) {
  mesh::Patch axis{.name = "axis", .tag = 0, .faces = {}, .nodes = {}};
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const Column& column = columns[c];
    const auto cell = flat.mesh.cells.nodes(c);
    for (std::size_t i = 0; i < cell.size(); ++i) {
      const mesh::NodeId a = cell[i], b = cell[(i + 1) % cell.size()];
      const auto on_axis = [&](mesh::NodeId n) {
        for (std::size_t k = 0; k < column.count; ++k) {
          if (flat.map.node[static_cast<std::size_t>(column.back[k])] == n) return column.front[k] == column.back[k];
        }
        return false;
      };
      if (on_axis(a) && on_axis(b)) axis.faces.add(mesh::ElementType::line2, {a, b});
    }
  }
  if (axis.faces.empty()) return;
  int tag = 0;
  for (const BoundaryPatch& p : m.patches) {
    ++tag;
    if (p.type == "empty" && p.face_count == 0) {
      axis.name = p.name;
      axis.tag = tag;
      break;
    }
  }
  if (axis.tag == 0) axis.tag = static_cast<int>(m.patches.size()) + 1;
  flat.mesh.patches.push_back(std::move(axis));
}

}  // namespace

bool is_2d(const PolyMesh& mesh) {
  return std::any_of(mesh.patches.begin(), mesh.patches.end(),
                     [](const BoundaryPatch& p) { return is_planar_type(p.type) && p.face_count > 0; });
}

FlatMesh flatten(const PolyMesh& m, const CellFaces& cells, const std::string& source) {
  const auto patches = planar_patches(m, source);
  const Planes planes =
      patches.front()->type == "empty" ? empty_planes(m, patches, source) : wedge_planes(m, patches, source);
  const std::vector<std::int64_t> back = back_faces(m, cells, planes, source);
  const std::vector<Column> cells_2d = columns(m, cells, back, planes, source);
  const Pairing pairing = pair_points(m, cells_2d, source);
  FlatMesh flat;
  flat.mesh.dimension = 2;
  flat.map.frames = planes.frames;
  flat.map.plane.assign(pairing.plane.begin(), pairing.plane.end());
  add_back_points(m, pairing, flat);
  add_cells(cells_2d, flat);
  add_side_patches(m, pairing, flat, source);
  if (planes.kind == "wedge") add_axis_patch(m, cells_2d, flat);
  flat.mesh.derive_node_sets();
  return flat;
}

}  // namespace hotmesh::io::foam
