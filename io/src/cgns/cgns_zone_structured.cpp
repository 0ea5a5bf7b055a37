// hotmesh io: structured CGNS zones. Cell (i, j[, k]) is the quad / hex of the nodes
// (i..i+1, j..j+1[, k..k+1]), numbered i fastest as CGNS stores them; a left-handed zone
// (the corner Jacobians of most cells negative) has its cells renumbered so that every cell is positively
// oriented. Boundary conditions become node sets (a face-centred range covers the nodes of
// its faces); cgns_assemble.cpp keeps the zone's boundary faces whose nodes are all in it.
#include <fmt/format.h>

#include "cgns/cgns_reader.hpp"
#include "hotmesh/core/input_error.hpp"

namespace hotmesh::io::cgns {
namespace {

/// The raw node (i, j, k) of a structured zone (0-based indices).
NodeId grid_node(const ZoneRecord& zone, cgsize_t i, cgsize_t j, cgsize_t k) {
  return zone.first_node + static_cast<NodeId>(i + zone.vertices[0] * (j + zone.vertices[1] * k));
}

/// The sum over the zone's cells of the sign of the Jacobian at their corner (i, j, k) with
/// the i, j, k numbering: negative for a left-handed zone.
long handedness(const RawMesh& raw, const ZoneRecord& zone) {
  const cgsize_t nk = raw.dimension == 3 ? zone.vertices[2] : 2;
  const auto at = [&](cgsize_t i, cgsize_t j, cgsize_t k) {
    return raw.points[static_cast<std::size_t>(grid_node(zone, i, j, k))];
  };
  long sum = 0;
  for (cgsize_t k = 0; k + 1 < nk; ++k) {
    for (cgsize_t j = 0; j + 1 < zone.vertices[1]; ++j) {
      for (cgsize_t i = 0; i + 1 < zone.vertices[0]; ++i) {
        const geometry::Vec3 o = at(i, j, k), a = at(i + 1, j, k) - o, b = at(i, j + 1, k) - o;
        double det = a.x * b.y - a.y * b.x;
        if (raw.dimension == 3) {
          const geometry::Vec3 c = at(i, j, k + 1) - o;
          det = a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) + a.z * (b.x * c.y - b.y * c.x);
        }
        sum += det > 0 ? 1 : (det < 0 ? -1 : 0);
      }
    }
  }
  return sum;
}

void add_cells(RawMesh& raw, const ZoneRecord& zone, bool mirrored) {
  const auto ni = zone.vertices[0], nj = zone.vertices[1], nk = raw.dimension == 3 ? zone.vertices[2] : 2;
  const auto node = [&](cgsize_t i, cgsize_t j, cgsize_t k) { return grid_node(zone, i, j, k); };
  for (cgsize_t k = 0; k + 1 < nk; ++k) {
    for (cgsize_t j = 0; j + 1 < nj; ++j) {
      for (cgsize_t i = 0; i + 1 < ni; ++i) {
        // Mirrored: i and j swap roles, which reverses the orientation.
        if (raw.dimension == 2) {
          if (mirrored) raw.cells.add(mesh::ElementType::quad4, {node(i, j, 0), node(i, j + 1, 0), node(i + 1, j + 1, 0), node(i + 1, j, 0)});
          else raw.cells.add(mesh::ElementType::quad4, {node(i, j, 0), node(i + 1, j, 0), node(i + 1, j + 1, 0), node(i, j + 1, 0)});
          continue;
        }
        if (mirrored) {
          raw.cells.add(mesh::ElementType::hex8, {node(i, j, k), node(i, j + 1, k), node(i + 1, j + 1, k), node(i + 1, j, k),
                                                   node(i, j, k + 1), node(i, j + 1, k + 1), node(i + 1, j + 1, k + 1),
                                                   node(i + 1, j, k + 1)});
        } else {
          raw.cells.add(mesh::ElementType::hex8, {node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k), node(i, j + 1, k),
                                                   node(i, j, k + 1), node(i + 1, j, k + 1), node(i + 1, j + 1, k + 1),
                                                   node(i, j + 1, k + 1)});
        }
      }
    }
  }
}

/// The structured direction a face-centred point set lies across: the one in which all its
/// points sit at the same side of the zone (location IFaceCenter.. names it).
int fixed_direction(const RawMesh& raw, const ZoneRecord& zone, CGNS_ENUMT(GridLocation_t) location,
                    const std::vector<cgsize_t>& points) {
  if (location == CGNS_ENUMV(IFaceCenter)) return 0;
  if (location == CGNS_ENUMV(JFaceCenter)) return 1;
  if (location == CGNS_ENUMV(KFaceCenter)) return 2;
  const auto d = static_cast<std::size_t>(raw.dimension);
  if (points.size() < d) return -1;
  for (std::size_t a = 0; a < d; ++a) {
    const cgsize_t side = points[a];
    if (side != 1 && side != zone.vertices[a]) continue;
    bool all = true;
    for (std::size_t p = a; p < points.size() && all; p += d) all = points[p] == side;
    if (all) return static_cast<int>(a);
  }
  return -1;
}

/// The nodes of the faces a face-centred point set names (each face: its index point and
/// the next vertices along the other directions).
std::vector<cgsize_t> face_vertices(const RawMesh& raw, const std::vector<cgsize_t>& faces, int fixed) {
  const auto d = static_cast<std::size_t>(raw.dimension);
  std::vector<cgsize_t> vertices;
  for (std::size_t f = 0; f + d <= faces.size(); f += d) {
    const std::size_t corners = std::size_t{1} << (d - 1);
    for (std::size_t c = 0; c < corners; ++c) {
      std::size_t bit = 0;
      for (std::size_t a = 0; a < d; ++a) {
        cgsize_t v = faces[f + a];
        if (static_cast<int>(a) != fixed) v += static_cast<cgsize_t>((c >> bit++) & 1u);
        vertices.push_back(v);
      }
    }
  }
  return vertices;
}

void read_bc(const File& file, RawMesh& raw, std::size_t z, int b) {
  const ZoneRecord& zone = raw.zones[z];
  const BcPoints given = read_bc_points(file, raw, zone, b);
  RawBc bc;
  bc.where = given.where;
  bc.patch = given.patch;
  bc.zone = z;
  bc.by_points = true;
  const auto dims = static_cast<std::size_t>(raw.dimension);
  std::vector<cgsize_t> points = expand_point_set(raw, given.set, given.data, raw.dimension, node_limits(zone), bc.where);
  if (given.location != CGNS_ENUMV(Vertex)) {
    const int fixed = fixed_direction(raw, zone, given.location, points);
    if (fixed < 0) {
      throw InputError::in(file.name(), fmt::format("{}: its {} points lie on no side of the zone", bc.where,
                                                    cg_GridLocationName(given.location)));
    }
    points = face_vertices(raw, points, fixed);
  }
  for (std::size_t p = 0; p + dims <= points.size(); p += dims) {
    for (std::size_t a = 0; a < dims; ++a) {
      if (points[p + a] < 1 || points[p + a] > zone.vertices[a]) {
        throw InputError::in(file.name(), fmt::format("{} reaches node index {} along {}, but the zone has {}", bc.where,
                                                      points[p + a], "ijk"[a], zone.vertices[a]));
      }
    }
    bc.nodes.push_back(raw_node(zone, points.data() + p, raw.dimension));
  }
  raw.bcs.push_back(std::move(bc));
}

}  // namespace

void read_structured_zone(const File& file, RawMesh& raw, std::size_t z) {
  ZoneRecord& zone = raw.zones[z];
  for (int d = 0; d < raw.dimension; ++d) {
    if (zone.vertices[static_cast<std::size_t>(d)] < 2) {
      throw InputError::in(file.name(), fmt::format("structured zone '{}' has {} nodes along direction {}: a zone of "
                                                    "cells needs at least 2",
                                                    zone.name, zone.vertices[static_cast<std::size_t>(d)], "ijk"[d]));
    }
  }
  add_cells(raw, zone, handedness(raw, zone) < 0);
  int bcs = 0;
  file.check(cg_nbocos(file.fn(), raw.base, zone.index, &bcs), fmt::format("zone '{}': reading its BCs", zone.name));
  for (int b = 1; b <= bcs; ++b) read_bc(file, raw, z, b);
}

}  // namespace hotmesh::io::cgns
