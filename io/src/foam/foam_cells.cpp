// hotmesh io: hexahedra, prisms, pyramids and tetrahedra from polyMesh faces (see
// foam_cells.hpp).
#include "foam/foam_cells.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "hotmesh/core/input_error.hpp"

namespace hotmesh::io::foam {
namespace {


/// The faces of one cell, each with its points in outward order (for messages).
struct OutwardFaces {
  std::vector<std::vector<std::int64_t>> faces;
};

OutwardFaces outward_faces(const PolyMesh& mesh, const CellFaces& cells, std::size_t c) {
  OutwardFaces out;
  for (auto i = cells.offsets[c]; i < cells.offsets[c + 1]; ++i) {
    const auto f = static_cast<std::size_t>(cells.faces[static_cast<std::size_t>(i)]);
    std::vector<std::int64_t> points(mesh.faces.nodes.begin() + mesh.faces.offsets[f],
                                     mesh.faces.nodes.begin() + mesh.faces.offsets[f + 1]);
    if (!cells.owned[static_cast<std::size_t>(i)]) std::reverse(points.begin(), points.end());
    out.faces.push_back(std::move(points));
  }
  return out;
}

/// True if every directed edge of the faces is in exactly one face and its reverse in one other.
bool closes(const OutwardFaces& cell) {
  std::vector<std::pair<std::int64_t, std::int64_t>> edges;
  for (const auto& f : cell.faces) {
    for (std::size_t i = 0; i < f.size(); ++i) edges.emplace_back(f[i], f[(i + 1) % f.size()]);
  }
  if (cell.faces.size() < 4) return false;
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const auto [a, b] = edges[i];
    if (a == b || (i > 0 && edges[i - 1] == edges[i])) return false;
    if (!std::binary_search(edges.begin(), edges.end(), std::pair{b, a})) return false;
  }
  return true;
}

/// "a prism", "a tetrahedron", ...: what a cell that is not a hexahedron looks like.
std::string shape_of(const OutwardFaces& cell) {
  std::size_t triangles = 0, quads = 0;
  for (const auto& f : cell.faces) {
    triangles += f.size() == 3;
    quads += f.size() == 4;
  }
  const std::size_t n = cell.faces.size();
  if (n == 0) return "no faces";
  std::string shape;
  if (n == 4 && triangles == 4) {
    shape = "a tetrahedron";
  } else if (n == 5 && triangles == 2 && quads == 3) {
    shape = "a prism";
  } else if (n == 5 && triangles == 4 && quads == 1) {
    shape = "a pyramid";
  } else if (n == 6 && quads == 6) {
    shape = "six quadrilaterals that do not close a hexahedron";
  } else {
    std::vector<std::size_t> sizes;
    for (const auto& f : cell.faces) sizes.push_back(f.size());
    shape = fmt::format("a polyhedron, faces of {} points", fmt::join(sizes, ", "));
  }
  return fmt::format("{} faces ({})", n, shape);
}

/// The faces of a cell with at most 6 faces of 3 or 4 points, each in outward order.
struct SmallCell {
  std::size_t count = 0;
  std::array<std::array<std::int64_t, 4>, 6> faces{};
  std::array<std::uint8_t, 6> sizes{};
  std::size_t triangles = 0, quads = 0;
};

std::optional<SmallCell> outward_small(const PolyMesh& mesh, const CellFaces& cells, std::size_t c) {
  SmallCell out;
  out.count = static_cast<std::size_t>(cells.offsets[c + 1] - cells.offsets[c]);
  if (out.count < 4 || out.count > 6) return std::nullopt;
  for (std::size_t k = 0; k < out.count; ++k) {
    const auto i = static_cast<std::size_t>(cells.offsets[c]) + k;
    const auto f = static_cast<std::size_t>(cells.faces[i]);
    const auto begin = static_cast<std::size_t>(mesh.faces.offsets[f]);
    const auto n = static_cast<std::size_t>(mesh.faces.offsets[f + 1]) - begin;
    if (n != 3 && n != 4) return std::nullopt;
    std::copy_n(mesh.faces.nodes.begin() + static_cast<std::ptrdiff_t>(begin), n, out.faces[k].begin());
    if (!cells.owned[i]) std::reverse(out.faces[k].begin(), out.faces[k].begin() + static_cast<std::ptrdiff_t>(n));
    out.sizes[k] = static_cast<std::uint8_t>(n);
    (n == 3 ? out.triangles : out.quads) += 1;
  }
  return out;
}

/// The element type the face counts of a cell imply, if any.
std::optional<mesh::ElementType> type_of(const SmallCell& cell) {
  if (cell.count == 4 && cell.triangles == 4) return mesh::ElementType::tet4;
  if (cell.count == 5 && cell.triangles == 4 && cell.quads == 1) return mesh::ElementType::pyramid5;
  if (cell.count == 5 && cell.triangles == 2 && cell.quads == 3) return mesh::ElementType::wedge6;
  if (cell.count == 6 && cell.quads == 6) return mesh::ElementType::hex8;
  return std::nullopt;
}

/// True if the cell's faces use exactly `points` points and each of its edges lies in
/// exactly two of its faces, once in each direction (a closed, consistently oriented
/// surface). Local point numbers i < 8, directed edges as bits i * 8 + j of a mask.
bool closes(const SmallCell& cell, std::size_t points) {
  std::array<std::int64_t, 8> seen{};
  std::size_t count = 0;
  const auto local = [&](std::int64_t p) -> int {
    for (std::size_t i = 0; i < count; ++i) {
      if (seen[i] == p) return static_cast<int>(i);
    }
    if (count == seen.size()) return -1;
    seen[count] = p;
    return static_cast<int>(count++);
  };
  std::uint64_t edges = 0;
  for (std::size_t k = 0; k < cell.count; ++k) {
    const std::size_t n = cell.sizes[k];
    std::array<int, 4> q{};
    for (std::size_t i = 0; i < n; ++i) {
      q[i] = local(cell.faces[k][i]);
      if (q[i] < 0) return false;
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (q[i] == q[(i + 1) % n]) return false;
      const std::uint64_t bit = std::uint64_t{1} << (q[i] * 8 + q[(i + 1) % n]);
      if (edges & bit) return false;
      edges |= bit;
    }
  }
  if (count != points) return false;
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 8; ++j) {
      if (((edges >> (i * 8 + j)) & 1U) != ((edges >> (j * 8 + i)) & 1U)) return false;
    }
  }
  return true;
}

/// The node joined to `node` by an edge of the cell that does not end in `bottom`, if
/// exactly one.
std::optional<std::int64_t> above(const SmallCell& cell, std::int64_t node, std::span<const std::int64_t> bottom) {
  std::optional<std::int64_t> found;
  for (std::size_t k = 0; k < cell.count; ++k) {
    const std::size_t n = cell.sizes[k];
    for (std::size_t i = 0; i < n; ++i) {
      if (cell.faces[k][i] != node) continue;
      for (const std::int64_t other : {cell.faces[k][(i + 1) % n], cell.faces[k][(i + n - 1) % n]}) {
        if (std::find(bottom.begin(), bottom.end(), other) != bottom.end()) continue;
        if (found && *found != other) return std::nullopt;
        found = other;
      }
    }
  }
  return found;
}

std::optional<FoamCell> element_from(const SmallCell& cell) {
  const auto type = type_of(cell);
  if (!type) return std::nullopt;
  const auto n = static_cast<std::size_t>(mesh::node_count(*type));
  if (!closes(cell, n)) return std::nullopt;
  // The bottom face: the first face of its size that the type has below its other nodes.
  const std::size_t bottom_size = *type == mesh::ElementType::tet4 || *type == mesh::ElementType::wedge6 ? 3 : 4;
  std::size_t b = 0;
  while (cell.sizes[b] != bottom_size) ++b;
  const auto& f = cell.faces[b];
  FoamCell out;
  out.type = *type;
  out.nodes[0] = f[0];  // reversed: right-hand normal into the cell
  for (std::size_t i = 1; i < bottom_size; ++i) out.nodes[i] = f[bottom_size - i];
  const std::span<const std::int64_t> bottom(out.nodes.data(), bottom_size);
  if (n == bottom_size + 1) {  // tetrahedron, pyramid: the apex is the one point off the bottom
    for (std::size_t k = 0; k < cell.count; ++k) {
      for (std::size_t i = 0; i < cell.sizes[k]; ++i) {
        if (std::find(bottom.begin(), bottom.end(), cell.faces[k][i]) == bottom.end()) out.nodes[bottom_size] = cell.faces[k][i];
      }
    }
    return out;
  }
  for (std::size_t i = 0; i < bottom_size; ++i) {  // prism, hexahedron: the top above the bottom
    const auto top = above(cell, out.nodes[i], bottom);
    if (!top) return std::nullopt;
    out.nodes[bottom_size + i] = *top;
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      if (out.nodes[i] == out.nodes[j]) return std::nullopt;
    }
  }
  return out;
}

}  // namespace

CellFaces cell_faces(const PolyMesh& mesh) {
  CellFaces cells;
  cells.offsets.assign(mesh.cell_count + 1, 0);
  for (const std::int64_t c : mesh.owner) ++cells.offsets[static_cast<std::size_t>(c) + 1];
  for (const std::int64_t c : mesh.neighbour) ++cells.offsets[static_cast<std::size_t>(c) + 1];
  for (std::size_t c = 0; c < mesh.cell_count; ++c) cells.offsets[c + 1] += cells.offsets[c];
  cells.faces.resize(static_cast<std::size_t>(cells.offsets.back()));
  cells.owned.resize(cells.faces.size());
  std::vector<std::int64_t> next(cells.offsets.begin(), cells.offsets.end() - 1);
  const auto add = [&](std::int64_t cell, std::size_t face, bool owned) {
    const auto at = static_cast<std::size_t>(next[static_cast<std::size_t>(cell)]++);
    cells.faces[at] = static_cast<std::int64_t>(face);
    cells.owned[at] = owned;
  };
  for (std::size_t f = 0; f < mesh.owner.size(); ++f) add(mesh.owner[f], f, true);
  for (std::size_t f = 0; f < mesh.neighbour.size(); ++f) add(mesh.neighbour[f], f, false);
  return cells;
}

std::vector<FoamCell> volume_cells(const PolyMesh& mesh, const CellFaces& cells, const std::string& source) {
  std::vector<FoamCell> out(mesh.cell_count);
  for (std::size_t c = 0; c < mesh.cell_count; ++c) {
    const std::optional<SmallCell> faces = outward_small(mesh, cells, c);
    const auto cell = faces ? element_from(*faces) : std::nullopt;
    if (cell) {
      out[c] = *cell;
      continue;
    }
    const OutwardFaces polyhedron = outward_faces(mesh, cells, c);
    if (!closes(polyhedron)) {
      const auto type = faces ? type_of(*faces) : std::nullopt;
      throw InputError::in(source, type ? fmt::format("cell {} has {} faces that do not close a {}", c, faces->count,
                                                      mesh::name(*type))
                                        : fmt::format("cell {} has {} that do not close a cell (each edge must be in "
                                                      "exactly two of its faces, once in each direction)",
                                                      c, shape_of(polyhedron)));
    }
    out[c].polyhedron = true;
  }
  return out;
}

}  // namespace hotmesh::io::foam
