// hotmesh io: a new OpenFOAM polyMesh from a hex mesh (hotmesh convert, write_mesh to a
// polyMesh folder; see hotmesh/io/foam.hpp). Faces are found by matching the cells' faces on
// their sorted nodes, bucketed by their smallest node. OpenFOAM's order: internal faces first,
// in upper-triangular order (by owner, then neighbour; owner < neighbour; nodes ordered so
// that the right-hand normal points from owner to neighbour), then the boundary faces patch
// after patch (normals outward). Points and cells keep the mesh's numbering.
#include <algorithm>
#include <array>
#include <cstring>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "hotmesh/geometry/input_error.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/foam.hpp"

namespace hotmesh::io {
namespace fs = std::filesystem;

namespace {

using mesh::CellId;
using mesh::NodeId;
using FaceKey = std::array<NodeId, 4>;
constexpr int kHexFaceCount = 6;

/// A face of the polyMesh: its nodes (as OpenFOAM orders them) and its cells.
struct FoamFace {
  std::array<NodeId, 4> nodes{};
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

/// The cell faces of a hex mesh, bucketed by smallest node; `partner` of cell face c*6+f is
/// the cell on its other side (-1 on the boundary).
class HexFaces {
 public:
  explicit HexFaces(const mesh::Mesh& m) : m_(m) {
    bucket_faces();
    match_partners();
  }

  std::array<NodeId, 4> nodes(std::int64_t cell_face) const {
    const auto cell = m_.cells.nodes(static_cast<std::size_t>(cell_face / kHexFaceCount));
    const mesh::LocalFace& local = mesh::faces(mesh::ElementType::hex8)[static_cast<std::size_t>(cell_face % kHexFaceCount)];
    return {cell[local.nodes[0]], cell[local.nodes[1]], cell[local.nodes[2]], cell[local.nodes[3]]};
  }
  CellId partner(std::int64_t cell_face) const { return partner_[static_cast<std::size_t>(cell_face)]; }

  /// The boundary cell face with these nodes (in any order), or -1.
  std::int64_t find_boundary(std::span<const NodeId> face) const {
    FaceKey key{face[0], face[1], face[2], face[3]};
    std::sort(key.begin(), key.end());
    const auto b = static_cast<std::size_t>(key[0]);
    for (std::int64_t i = start_[b]; i < start_[b + 1]; ++i) {
      const std::int64_t cf = bucket_[static_cast<std::size_t>(i)];
      if (partner(cf) < 0 && sorted(cf) == key) return cf;
    }
    return -1;
  }

 private:
  FaceKey sorted(std::int64_t cell_face) const {
    FaceKey key = nodes(cell_face);
    std::sort(key.begin(), key.end());
    return key;
  }

  void bucket_faces() {
    const std::int64_t count = static_cast<std::int64_t>(m_.cell_count()) * kHexFaceCount;
    start_.assign(m_.node_count() + 1, 0);
    for (std::int64_t cf = 0; cf < count; ++cf) ++start_[static_cast<std::size_t>(sorted(cf)[0]) + 1];
    for (std::size_t n = 0; n < m_.node_count(); ++n) start_[n + 1] += start_[n];
    bucket_.resize(static_cast<std::size_t>(count));
    std::vector<std::int64_t> fill(start_.begin(), start_.end() - 1);
    for (std::int64_t cf = 0; cf < count; ++cf) bucket_[static_cast<std::size_t>(fill[static_cast<std::size_t>(sorted(cf)[0])]++)] = cf;
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
                           std::to_string(m_.cell_id(static_cast<CellId>(in_bucket[i].second / kHexFaceCount))) +
                           " and more)");
        }
        const std::int64_t a = in_bucket[i].second, c = in_bucket[i + 1].second;
        partner_[static_cast<std::size_t>(a)] = static_cast<CellId>(c / kHexFaceCount);
        partner_[static_cast<std::size_t>(c)] = static_cast<CellId>(a / kHexFaceCount);
        ++i;
      }
    }
  }

  const mesh::Mesh& m_;
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

void add_internal_faces(const mesh::Mesh& m, const HexFaces& hex, PolyMesh& poly) {
  std::vector<std::pair<CellId, int>> upper;  // (neighbour, local face) of one cell
  for (CellId c = 0; c < static_cast<CellId>(m.cell_count()); ++c) {
    upper.clear();
    for (int f = 0; f < kHexFaceCount; ++f) {
      const CellId other = hex.partner(std::int64_t{c} * kHexFaceCount + f);
      if (other > c) upper.emplace_back(other, f);
    }
    std::sort(upper.begin(), upper.end());
    for (const auto& [other, f] : upper) poly.faces.push_back({hex.nodes(std::int64_t{c} * kHexFaceCount + f), c, other});
  }
  poly.internal = poly.faces.size();
}

void add_boundary_faces(const mesh::Mesh& m, const HexFaces& hex, PolyMesh& poly) {
  std::vector<char> taken(m.cell_count() * kHexFaceCount, 0);
  for (const mesh::Patch& patch : m.patches) {
    FoamPatch fp{patch.name, foam_patch_type(patch.name), poly.faces.size(), patch.faces.size()};
    for (std::size_t i = 0; i < patch.faces.size(); ++i) {
      const std::int64_t cf = patch.faces.nodes(i).size() == 4 ? hex.find_boundary(patch.faces.nodes(i)) : -1;
      if (cf < 0 || taken[static_cast<std::size_t>(cf)]) {
        throw InputError(fmt::format("face {} of patch '{}' is {}", i + 1, patch.name,
                                     cf < 0 ? "not a boundary face of a cell" : "in another patch too"));
      }
      taken[static_cast<std::size_t>(cf)] = 1;
      poly.faces.push_back({hex.nodes(cf), static_cast<CellId>(cf / kHexFaceCount), -1});
    }
    poly.patches.push_back(fp);
  }
  FoamPatch rest{"defaultFaces", "wall", poly.faces.size(), 0};
  for (std::int64_t cf = 0; cf < static_cast<std::int64_t>(taken.size()); ++cf) {
    if (hex.partner(cf) >= 0 || taken[static_cast<std::size_t>(cf)]) continue;
    poly.faces.push_back({hex.nodes(cf), static_cast<CellId>(cf / kHexFaceCount), -1});
    ++rest.count;
  }
  if (rest.count > 0) {
    spdlog::warn("{} boundary faces are in no patch: written as the wall patch defaultFaces", rest.count);
    poly.patches.push_back(rest);
  }
}

PolyMesh poly_mesh(const mesh::Mesh& m) {
  const HexFaces hex(m);
  PolyMesh poly;
  poly.faces.reserve(m.cell_count() * 3 + m.cell_count() / 2);
  add_internal_faces(m, hex, poly);
  add_boundary_faces(m, hex, poly);
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
    append_labels(out, poly.faces.size() + 1, true, [](std::size_t i) { return 4 * i; });
    out.push_back('\n');
    append_labels(out, 4 * poly.faces.size(), true, [&](std::size_t i) { return poly.faces[i / 4].nodes[i % 4]; });
    return out += kTail;
  }
  std::string out = header(false, "faceList", "faces");
  auto it = std::back_inserter(out);
  fmt::format_to(it, "{}\n(\n", poly.faces.size());
  for (const FoamFace& f : poly.faces) fmt::format_to(it, "4({} {} {} {})\n", f.nodes[0], f.nodes[1], f.nodes[2], f.nodes[3]);
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
                         "hotmesh writes new OpenFOAM meshes from 3D hex meshes only; a 2D mesh would need "
                         "extruding into a one-cell-thick case (write it as .msh or .cgns instead)");
  }
  for (std::size_t c = 0; c < m.cell_count(); ++c) {
    if (m.cells.type(c) != mesh::ElementType::hex8) {
      throw InputError::in(path.string(), fmt::format("hotmesh writes new OpenFOAM meshes of hexahedra only; cell {} "
                                                      "is a {}",
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
