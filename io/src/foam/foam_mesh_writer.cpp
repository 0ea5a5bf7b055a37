// hotmesh io: a new OpenFOAM polyMesh from a 3D mesh of hexahedra, prisms, pyramids and
// tetrahedra (hotmesh convert, write_mesh to a polyMesh folder; see hotmesh/io/foam.hpp).
// Each cell's faces are those of its type (mesh::faces(), outward, triangles and quads). Faces are found by matching the cells' faces on
// their sorted nodes, bucketed by their smallest node. OpenFOAM's order: internal faces first,
// in upper-triangular order (by owner, then neighbour; owner < neighbour; nodes ordered so
// that the right-hand normal points from owner to neighbour), then the boundary faces patch
// after patch (normals outward). Points and cells keep the mesh's numbering.
#include <algorithm>
#include <array>
#include <cstring>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/foam.hpp"

namespace hotmesh::io {
namespace fs = std::filesystem;

namespace {

using mesh::CellId;
using mesh::NodeId;
using FaceKey = std::array<NodeId, 4>;  ///< a face's nodes sorted, -1 first for a triangle

/// A face of the polyMesh: its nodes (as OpenFOAM orders them) and its cells.
struct FoamFace {
  std::array<NodeId, 4> nodes{};
  std::uint8_t count = 4;
  CellId owner = 0, neighbour = -1;
};

struct FoamPatch {
  std::string name, type;
  std::size_t start = 0, count = 0;
};

struct PolyMesh {
  std::vector<FoamFace> faces;  ///< internal, then boundary by patch
  std::size_t internal = 0;
  std::vector<FoamPatch> patches;
};

/// The faces of every cell (mesh::faces(type), outward), numbered cell after cell: cell c's
/// are first_[c] .. first_[c+1]-1. They are bucketed by smallest node; `partner` of a cell
/// face is the cell on its other side (-1 on the boundary).
class CellFaces {
 public:
  explicit CellFaces(const mesh::Mesh& m) : m_(m) {
    first_.assign(m.cell_count() + 1, 0);
    for (std::size_t c = 0; c < m.cell_count(); ++c) first_[c + 1] = first_[c] + static_cast<std::int64_t>(mesh::faces(m.cells.type(c)).size());
    cell_of_.resize(static_cast<std::size_t>(first_.back()));
    for (std::size_t c = 0; c < m.cell_count(); ++c) {
      std::fill(cell_of_.begin() + first_[c], cell_of_.begin() + first_[c + 1], static_cast<CellId>(c));
    }
    bucket_faces();
    match_partners();
  }

  std::int64_t first(CellId c) const { return first_[static_cast<std::size_t>(c)]; }
  std::int64_t count() const { return first_.back(); }
  CellId cell(std::int64_t cell_face) const { return cell_of_[static_cast<std::size_t>(cell_face)]; }

  FoamFace face(std::int64_t cell_face) const {
    const CellId c = cell(cell_face);
    const auto nodes = m_.cells.nodes(static_cast<std::size_t>(c));
    const mesh::LocalFace& local =
        mesh::faces(m_.cells.type(static_cast<std::size_t>(c)))[static_cast<std::size_t>(cell_face - first(c))];
    FoamFace f;
    f.count = local.count;
    for (std::size_t i = 0; i < local.count; ++i) f.nodes[i] = nodes[local.nodes[i]];
    f.owner = c;
    return f;
  }
  CellId partner(std::int64_t cell_face) const { return partner_[static_cast<std::size_t>(cell_face)]; }

  /// The boundary cell face with these nodes (in any order), or -1.
  std::int64_t find_boundary(std::span<const NodeId> nodes) const {
    if (nodes.size() != 3 && nodes.size() != 4) return -1;
    const FaceKey key = sorted(nodes);
    const auto b = static_cast<std::size_t>(key[4 - nodes.size()]);
    for (std::int64_t i = start_[b]; i < start_[b + 1]; ++i) {
      const std::int64_t cf = bucket_[static_cast<std::size_t>(i)];
      if (partner(cf) < 0 && sorted(cf) == key) return cf;
    }
    return -1;
  }

 private:
  static FaceKey sorted(std::span<const NodeId> nodes) {
    FaceKey key{-1, -1, -1, -1};
    std::copy(nodes.begin(), nodes.end(), key.begin() + static_cast<std::ptrdiff_t>(4 - nodes.size()));
    std::sort(key.begin(), key.end());
    return key;
  }
  FaceKey sorted(std::int64_t cell_face) const {
    const FoamFace f = face(cell_face);
    return sorted(std::span<const NodeId>(f.nodes.data(), f.count));
  }
  /// The smallest node of a cell face (its bucket).
  std::size_t smallest(std::int64_t cell_face) const {
    const FaceKey key = sorted(cell_face);
    return static_cast<std::size_t>(key[0] < 0 ? key[1] : key[0]);
  }

  void bucket_faces() {
    start_.assign(m_.node_count() + 1, 0);
    for (std::int64_t cf = 0; cf < count(); ++cf) ++start_[smallest(cf) + 1];
    for (std::size_t n = 0; n < m_.node_count(); ++n) start_[n + 1] += start_[n];
    bucket_.resize(static_cast<std::size_t>(count()));
    std::vector<std::int64_t> fill(start_.begin(), start_.end() - 1);
    for (std::int64_t cf = 0; cf < count(); ++cf) bucket_[static_cast<std::size_t>(fill[smallest(cf)]++)] = cf;
  }

  void match_partners() {
    partner_.assign(bucket_.size(), -1);
    std::vector<std::pair<FaceKey, std::int64_t>> in_bucket;
    for (std::size_t b = 0; b + 1 < start_.size(); ++b) {
      in_bucket.clear();
      for (std::int64_t i = start_[b]; i < start_[b + 1]; ++i) {
        const std::int64_t cf = bucket_[static_cast<std::size_t>(i)];
        in_bucket.emplace_back(sorted(cf), cf);
      }
      std::sort(in_bucket.begin(), in_bucket.end());
      for (std::size_t i = 0; i + 1 < in_bucket.size(); ++i) {
        if (in_bucket[i].first != in_bucket[i + 1].first) continue;
        if (i + 2 < in_bucket.size() && in_bucket[i + 2].first == in_bucket[i].first) {
          throw InputError("a face is shared by more than two cells (cells " +
                           std::to_string(m_.cell_id(cell(in_bucket[i].second))) + " and more)");
        }
        const std::int64_t a = in_bucket[i].second, c = in_bucket[i + 1].second;
        partner_[static_cast<std::size_t>(a)] = cell(c);
        partner_[static_cast<std::size_t>(c)] = cell(a);
        ++i;
      }
    }
  }

  const mesh::Mesh& m_;
  std::vector<std::int64_t> first_;
  std::vector<CellId> cell_of_;
  std::vector<std::int64_t> start_, bucket_;
  std::vector<CellId> partner_;
};

/// `patch` for inflow, outflow and periodic sides (names starting or ending with inlet,
/// outlet, inflow, outflow, or starting with per_ or periodic), `wall` for the others.
std::string foam_patch_type(std::string_view name) {
  for (const std::string_view word : {"inlet", "outlet", "inflow", "outflow"}) {
    if (name.starts_with(word) || name.ends_with(word)) return "patch";
  }
  if (name.starts_with("per_") || name.starts_with("periodic")) return "patch";
  return "wall";
}

void add_internal_faces(const mesh::Mesh& m, const CellFaces& cf, PolyMesh& poly) {
  std::vector<std::pair<CellId, std::int64_t>> upper;  // (neighbour, cell face) of one cell
  for (CellId c = 0; c < static_cast<CellId>(m.cell_count()); ++c) {
    upper.clear();
    for (std::int64_t f = cf.first(c); f < cf.first(c + 1); ++f) {
      const CellId other = cf.partner(f);
      if (other > c) upper.emplace_back(other, f);
    }
    std::sort(upper.begin(), upper.end());
    for (const auto& [other, f] : upper) {
      FoamFace face = cf.face(f);
      face.neighbour = other;
      poly.faces.push_back(face);
    }
  }
  poly.internal = poly.faces.size();
}

void add_boundary_faces(const mesh::Mesh& m, const CellFaces& cf, PolyMesh& poly) {
  std::vector<char> taken(static_cast<std::size_t>(cf.count()), 0);
  for (const mesh::Patch& patch : m.patches) {
    FoamPatch fp{patch.name, foam_patch_type(patch.name), poly.faces.size(), patch.faces.size()};
    for (std::size_t i = 0; i < patch.faces.size(); ++i) {
      const std::int64_t f = cf.find_boundary(patch.faces.nodes(i));
      if (f < 0 || taken[static_cast<std::size_t>(f)]) {
        throw InputError(fmt::format("face {} of patch '{}' is {}", i + 1, patch.name,
                                     f < 0 ? "not a boundary face of a cell" : "in another patch too"));
      }
      taken[static_cast<std::size_t>(f)] = 1;
      poly.faces.push_back(cf.face(f));
    }
    poly.patches.push_back(fp);
  }
  FoamPatch rest{"defaultFaces", "wall", poly.faces.size(), 0};
  for (std::int64_t f = 0; f < cf.count(); ++f) {
    if (cf.partner(f) >= 0 || taken[static_cast<std::size_t>(f)]) continue;
    poly.faces.push_back(cf.face(f));
    ++rest.count;
  }
  if (rest.count > 0) {
    spdlog::warn("{} boundary faces are in no patch: written as the wall patch defaultFaces", rest.count);
    poly.patches.push_back(rest);
  }
}

PolyMesh poly_mesh(const mesh::Mesh& m) {
  const CellFaces cell_faces(m);
  PolyMesh poly;
  poly.faces.reserve(static_cast<std::size_t>(cell_faces.count() / 2 + cell_faces.count() / 12));
  add_internal_faces(m, cell_faces, poly);
  add_boundary_faces(m, cell_faces, poly);
  return poly;
}

// ---- the files ----

std::string header(bool binary, std::string_view cls, std::string_view object, std::string_view note = {}) {
  return fmt::format(
      "/*--------------------------------*- C++ -*----------------------------------*\\\n"
      "  written by hotmesh\n"
      "\\*---------------------------------------------------------------------------*/\n"
      "FoamFile\n{{\n    version     2.0;\n    format      {};\n    arch        \"LSB;label=32;scalar=64\";\n"
      "    class       {};\n{}    location    \"constant/polyMesh\";\n    object      {};\n}}\n"
      "// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n\n",
      binary ? "binary" : "ascii", cls, note.empty() ? std::string() : fmt::format("    note        \"{}\";\n", note),
      object);
}

constexpr std::string_view kTail = "\n\n// ************************************************************************* //\n";

template <class T>
void append_raw(std::string& out, const T& value) {
  char raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  out.append(raw, sizeof(T));
}

/// `n` labels label(0..n) as an OpenFOAM labelList body.
template <class Label>
void append_labels(std::string& out, std::size_t n, bool binary, Label label) {
  fmt::format_to(std::back_inserter(out), "{}\n(", n);
  if (binary) {
    out.reserve(out.size() + 4 * n + 2);
    for (std::size_t i = 0; i < n; ++i) append_raw(out, static_cast<std::int32_t>(label(i)));
  } else {
    auto it = std::back_inserter(out);
    for (std::size_t i = 0; i < n; ++i) fmt::format_to(it, "\n{}", label(i));
    out.push_back('\n');
  }
  out.push_back(')');
}

std::string points_file(std::span<const geometry::Vec3> points, bool binary) {
  std::string out = header(binary, "vectorField", "points");
  fmt::format_to(std::back_inserter(out), "{}\n(", points.size());
  if (binary) {
    out.reserve(out.size() + 24 * points.size() + kTail.size() + 2);
    for (const geometry::Vec3& p : points) {
      for (const double c : {p.x, p.y, p.z}) append_raw(out, c);
    }
  } else {
    auto it = std::back_inserter(out);
    for (const geometry::Vec3& p : points) fmt::format_to(it, "\n({} {} {})", p.x, p.y, p.z);
    out.push_back('\n');
  }
  out.push_back(')');
  return out += kTail;
}

std::string faces_file(const PolyMesh& poly, bool binary) {
  if (binary) {  // faceCompactList: the offsets, then the nodes
    std::string out = header(true, "faceCompactList", "faces");
    std::vector<std::size_t> offsets{0};
    std::vector<NodeId> nodes;
    for (const FoamFace& f : poly.faces) {
      nodes.insert(nodes.end(), f.nodes.begin(), f.nodes.begin() + f.count);
      offsets.push_back(nodes.size());
    }
    append_labels(out, offsets.size(), true, [&](std::size_t i) { return offsets[i]; });
    out.push_back('\n');
    append_labels(out, nodes.size(), true, [&](std::size_t i) { return nodes[i]; });
    return out += kTail;
  }
  std::string out = header(false, "faceList", "faces");
  auto it = std::back_inserter(out);
  fmt::format_to(it, "{}\n(\n", poly.faces.size());
  for (const FoamFace& f : poly.faces) {
    if (f.count == 3) {
      fmt::format_to(it, "3({} {} {})\n", f.nodes[0], f.nodes[1], f.nodes[2]);
    } else {
      fmt::format_to(it, "4({} {} {} {})\n", f.nodes[0], f.nodes[1], f.nodes[2], f.nodes[3]);
    }
  }
  out.push_back(')');
  return out += kTail;
}

std::string size_note(const mesh::Mesh& m, const PolyMesh& poly) {
  return fmt::format("nPoints:{}  nCells:{}  nFaces:{}  nInternalFaces:{}", m.node_count(), m.cell_count(),
                     poly.faces.size(), poly.internal);
}

std::string owner_file(const mesh::Mesh& m, const PolyMesh& poly, bool binary) {
  std::string out = header(binary, "labelList", "owner", size_note(m, poly));
  append_labels(out, poly.faces.size(), binary, [&](std::size_t i) { return poly.faces[i].owner; });
  return out += kTail;
}

std::string neighbour_file(const mesh::Mesh& m, const PolyMesh& poly, bool binary) {
  std::string out = header(binary, "labelList", "neighbour", size_note(m, poly));
  append_labels(out, poly.internal, binary, [&](std::size_t i) { return poly.faces[i].neighbour; });
  return out += kTail;
}

std::string boundary_file(const PolyMesh& poly) {
  std::string out = header(false, "polyBoundaryMesh", "boundary");
  auto it = std::back_inserter(out);
  fmt::format_to(it, "{}\n(\n", poly.patches.size());
  for (const FoamPatch& p : poly.patches) {
    fmt::format_to(it,
                   "    {}\n    {{\n        type            {};\n        inGroups        List<word> 1({});\n"
                   "        nFaces          {};\n        startFace       {};\n    }}\n",
                   p.name, p.type, p.type, p.count, p.start);
  }
  out.push_back(')');
  return out += kTail;
}

void check_writable(const fs::path& path, const mesh::Mesh& m) {
  if (m.dimension != 3) {
    throw InputError::in(path.string(),
                         "hotmesh writes new OpenFOAM meshes from 3D meshes only; a 2D mesh would need "
                         "extruding into a one-cell-thick case (write it as .msh or .cgns instead)");
  }
  for (std::size_t c = 0; c < m.cell_count(); ++c) {
    if (mesh::dimension(m.cells.type(c)) != 3) {
      throw InputError::in(path.string(), fmt::format("cell {} is a {}: an OpenFOAM mesh is made of volume cells",
                                                      m.cell_id(static_cast<CellId>(c)), mesh::name(m.cells.type(c))));
    }
  }
}

}  // namespace

fs::path foam_output_folder(const fs::path& path) {
  return path.filename() == "polyMesh" ? path : path / "constant" / "polyMesh";
}

void write_foam(const fs::path& path, const mesh::Mesh& m, std::span<const geometry::Vec3> points,
                const FoamWriteOptions& options) {
  check_writable(path, m);
  PolyMesh poly;
  try {
    poly = poly_mesh(m);
  } catch (const InputError& e) {
    throw InputError::in(path.string(), e.what());
  }
  const fs::path folder = foam_output_folder(path);
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw InputError::in(folder.string(), "cannot create the folder: " + ec.message());
  const bool binary = options.binary;
  write_file_atomically(folder / "points", points_file(points, binary));
  write_file_atomically(folder / "faces", faces_file(poly, binary));
  write_file_atomically(folder / "owner", owner_file(m, poly, binary));
  write_file_atomically(folder / "neighbour", neighbour_file(m, poly, binary));
  write_file_atomically(folder / "boundary", boundary_file(poly));
}

}  // namespace hotmesh::io
