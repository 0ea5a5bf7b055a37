// hotmesh io: reading an OpenFOAM polyMesh folder (see hotmesh/io/foam.hpp). Each of the five
// files is read (gunzipped if it is `name.gz`), its lists checked against the others, then
// the cells built as hexahedra, prisms, pyramids and tetrahedra, polyhedra as their pieces
// (3D), or flattened to quads and triangles (2D cases).
#include <algorithm>
#include <functional>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "foam/foam_2d.hpp"
#include "foam/foam_cells.hpp"
#include "foam/foam_file.hpp"
#include "foam/foam_polyhedra.hpp"
#include "foam/foam_write_back.hpp"
#include "gzip.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/foam.hpp"

namespace hotmesh::io {
namespace fs = std::filesystem;

namespace {

bool is_file(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

}  // namespace

bool is_foam_path(const fs::path& path) {
  std::error_code ec;
  return fs::is_directory(path, ec) || path.filename() == "polyMesh";
}

fs::path foam_mesh_folder(const fs::path& path) {
  if (is_file(path / "points") || is_file(path / "points.gz")) return path;
  const fs::path in_case = path / "constant" / "polyMesh";
  std::error_code ec;
  if (fs::is_directory(in_case, ec)) return in_case;
  throw InputError::in(path.string(),
                       "is neither an OpenFOAM polyMesh folder (no points or points.gz in it) nor a "
                       "case folder with constant/polyMesh");
}

namespace foam {
namespace {

/// One file of the polyMesh, plain or gzipped, uncompressed in memory.
struct FoamText {
  fs::path path;
  bool gzipped = false;
  std::string content;
};

/// What a file's content can need, from its (first) list's count: at most `count.max_count`
/// entries (what the files read before allow) of at most `entry_bytes(header)` bytes each.
struct ContentBound {
  std::string what;  ///< the list's entries, as its messages name them ("points")
  ListBound count;
  std::function<std::size_t(const FoamHeader&)> entry_bytes;
};

// The most text an entry takes as OpenFOAM writes it (with room to spare): a label (up to 20
// digits and a sign), a point of three scalars (17 significant digits and an exponent each),
// a face of 8 points on average (hotmesh's cells have faces of 3 and 4), a patch entry.
constexpr std::size_t kAsciiLabelBytes = 24;
constexpr std::size_t kAsciiPointBytes = 128;
constexpr std::size_t kFacePointsOnAverage = 8;
constexpr std::size_t kPatchBytes = 4096;
constexpr std::size_t kEmptyPatches = 1000;  ///< patches without faces a boundary may list
/// A gzipped file's header and list count are read from the first kHeadBytes of its content;
/// after its list, kTailBytes of closing text (comments) may follow.
constexpr std::size_t kHeadBytes = 64 << 10;
constexpr std::size_t kTailBytes = 64 << 10;

std::size_t label_bytes(const FoamHeader& h) {
  return h.binary ? static_cast<std::size_t>(h.label_bytes) : kAsciiLabelBytes;
}

/// The content of a gzipped file, decompressed no further than its header's count can need
/// (a few MB of gzip data can expand to GBs): the header and count are read from its first
/// part, the count checked against `bound.count`, then the whole inflated up to that bound.
std::string gunzip_bounded(std::string_view compressed, const std::string& source, const ContentBound& bound) {
  detail::GunzipHead head = detail::gunzip_head(compressed, source, kHeadBytes);
  if (head.whole) return std::move(head.content);
  FoamCursor in(head.content, source);
  in.read_header();
  const std::size_t n = list_count(in, bound.what, bound.count);
  const std::size_t entry = bound.entry_bytes(in.header());
  return detail::gunzip(compressed, source, in.position() + n * entry + kTailBytes,
                        fmt::format("what {} {} can need (at most {} bytes each, after a header of {} bytes)", n,
                                    bound.what, entry, in.position()));
}

FoamText read_foam_text(const fs::path& folder, const std::string& name, const ContentBound& bound) {
  FoamText text;
  text.path = folder / name;
  if (!is_file(text.path)) {
    text.path = folder / (name + ".gz");
    text.gzipped = true;
    if (!is_file(text.path)) {
      throw InputError::in(folder.string(),
                           fmt::format("the polyMesh folder has no '{}' file (nor {}.gz)", name, name));
    }
  }
  text.content = read_file(text.path);
  if (text.gzipped) text.content = gunzip_bounded(text.content, text.path.string(), bound);
  return text;
}

/// The faces, read first: nothing bounds their count but their own file. Returns its path.
std::string read_faces_file(const fs::path& folder, PolyMesh& mesh) {
  const FoamText text = read_foam_text(folder, "faces", {"faces", {}, [](const FoamHeader& h) {
                                                           return (1 + kFacePointsOnAverage) * label_bytes(h) + 16;
                                                         }});
  FoamCursor in(text.content, text.path.string());
  in.read_header();
  mesh.faces = read_faces(in);
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto begin = mesh.faces.offsets[f], end = mesh.faces.offsets[f + 1];
    if (end - begin < 3) {
      throw InputError::in(in.source(), fmt::format("face {} has {} points (a face needs at least 3)", f, end - begin));
    }
  }
  return in.source();
}

/// The points, no more than the faces can refer to (every point of a mesh is a point of a
/// face: OpenFOAM's checkMesh fails on unused points).
PointsFile read_points(const fs::path& folder, PolyMesh& mesh) {
  const std::size_t labels = mesh.faces.nodes.size();
  const ContentBound bound{
      "points",
      {.max_count = labels, .why_count = fmt::format("the faces refer to at most {} points (their lists hold {} point "
                                                     "labels in all)",
                                                     labels, labels)},
      [](const FoamHeader& h) { return h.binary ? 3 * static_cast<std::size_t>(h.scalar_bytes) : kAsciiPointBytes; }};
  FoamText text = read_foam_text(folder, "points", bound);
  PointsFile file;
  FoamCursor in(text.content, text.path.string());
  in.read_header();
  in.skip_space();
  file.list_begin = in.position();
  mesh.points = read_vector_list(in, bound.what, bound.count);
  file.list_end = in.position();
  file.name = text.path.filename().string();
  file.gzipped = text.gzipped;
  file.header = in.header();
  file.content = std::move(text.content);
  return file;
}

/// Every face's points are points of the points file.
void check_face_points(const PolyMesh& mesh, const std::string& faces_source) {
  const auto points = static_cast<std::int64_t>(mesh.points.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    for (auto i = mesh.faces.offsets[f]; i < mesh.faces.offsets[f + 1]; ++i) {
      const std::int64_t p = mesh.faces.nodes[static_cast<std::size_t>(i)];
      if (p < 0 || p >= points) {
        throw InputError::in(faces_source, fmt::format("face {} refers to point {}, but the points file has {} points "
                                                       "(0 to {})",
                                                       f, p, points, points - 1));
      }
    }
  }
}

/// Owner (one per face) or neighbour (one per internal face): cell labels >= 0, and where they
/// come from.
struct CellLabels {
  std::vector<std::int64_t> cells;
  std::string source;
};

CellLabels read_cells_of_faces(const fs::path& folder, const std::string& name, std::size_t faces) {
  const bool owner = name == "owner";
  const ContentBound bound{fmt::format("{} cells", name),
                           {.max_count = faces,
                            .why_count = fmt::format("there are {} faces (the faces file), {} each", faces,
                                                     owner ? "one owner" : "at most one neighbour")},
                           label_bytes};
  const FoamText text = read_foam_text(folder, name, bound);
  FoamCursor in(text.content, text.path.string());
  in.read_header();
  CellLabels labels{read_label_list(in, bound.what, bound.count), in.source()};
  if (owner && labels.cells.size() != faces) {
    throw InputError::in(in.source(), fmt::format("{} cells are listed for {} faces (the faces file): there must be "
                                                  "one owner per face",
                                                  labels.cells.size(), faces));
  }
  if (!owner && labels.cells.size() == faces) {
    // OpenFOAM 1.x padded the neighbours to one per face with -1 for the boundary faces;
    // OpenFOAM reads such a list (polyMesh::initMesh) as the neighbours before the first -1.
    const auto padding = std::find(labels.cells.begin(), labels.cells.end(), -1);
    const auto other = std::find_if(padding, labels.cells.end(), [](std::int64_t c) { return c != -1; });
    if (other != labels.cells.end()) {
      throw InputError::in(in.source(), fmt::format("face {} has neighbour cell {} after the padding of -1 that "
                                                    "starts at face {} (one neighbour per face, -1 for the boundary "
                                                    "faces, which follow the internal ones)",
                                                    other - labels.cells.begin(), *other,
                                                    padding - labels.cells.begin()));
    }
    labels.cells.erase(padding, labels.cells.end());
  }
  const auto bad = std::find_if(labels.cells.begin(), labels.cells.end(), [](std::int64_t c) { return c < 0; });
  if (bad != labels.cells.end()) {
    throw InputError::in(in.source(), fmt::format("face {} has {} cell {}, not a cell number",
                                                  bad - labels.cells.begin(), name, *bad));
  }
  return labels;
}

/// Every cell label below the number of cells the faces can make, before a label sizes
/// anything: a cell has at least 4 faces, and each face one owner and at most one neighbour.
void check_cell_labels(const CellLabels& owner, const CellLabels& neighbour) {
  const std::size_t max_cells = (owner.cells.size() + neighbour.cells.size()) / 4;
  for (const auto& [labels, name] : {std::pair{&owner, "owner"}, std::pair{&neighbour, "neighbour"}}) {
    const auto bad = std::find_if(labels->cells.begin(), labels->cells.end(),
                                  [&](std::int64_t c) { return static_cast<std::size_t>(c) >= max_cells; });
    if (bad == labels->cells.end()) continue;
    throw InputError::in(labels->source,
                         fmt::format("face {} has {} cell {}, but {} faces ({} of them internal) make at most {} "
                                     "cells (a cell has at least 4 faces)",
                                     bad - labels->cells.begin(), name, *bad, owner.cells.size(),
                                     neighbour.cells.size(), max_cells));
  }
}

void read_boundary_file(const fs::path& folder, PolyMesh& mesh) {
  const std::size_t internal = mesh.neighbour.size(), faces = mesh.faces.size();
  const ContentBound bound{
      "patches",
      {.max_count = faces + kEmptyPatches,
       .why_count = fmt::format("there are {} faces, and a boundary lists at most {} patches without faces",
                                faces, kEmptyPatches)},
      [](const FoamHeader&) { return kPatchBytes; }};
  const FoamText text = read_foam_text(folder, "boundary", bound);
  FoamCursor in(text.content, text.path.string());
  in.read_header();
  mesh.patches = read_boundary(in);
  for (const BoundaryPatch& p : mesh.patches) {
    const auto start = static_cast<std::size_t>(p.start_face), end = start + static_cast<std::size_t>(p.face_count);
    if (p.face_count > 0 && (start < internal || end > faces)) {
      in.fail_at(p.position, fmt::format("patch '{}' has faces {} to {}, but the boundary faces are {} to {}", p.name,
                                         start, end - 1, internal, faces - 1));
    }
  }
}

PolyMesh read_poly_mesh(const fs::path& folder, PointsFile& points_file) {
  PolyMesh mesh;
  const std::string faces_source = read_faces_file(folder, mesh);
  points_file = read_points(folder, mesh);
  check_face_points(mesh, faces_source);
  const CellLabels owner = read_cells_of_faces(folder, "owner", mesh.faces.size());
  const CellLabels neighbour = read_cells_of_faces(folder, "neighbour", mesh.faces.size());
  check_cell_labels(owner, neighbour);
  mesh.owner = owner.cells;
  mesh.neighbour = neighbour.cells;
  for (std::size_t f = 0; f < mesh.neighbour.size(); ++f) {
    if (mesh.neighbour[f] == mesh.owner[f]) {
      throw InputError::in(neighbour.source,
                           fmt::format("face {} has cell {} as both owner and neighbour", f, mesh.owner[f]));
    }
  }
  std::int64_t last = -1;
  for (const std::int64_t c : mesh.owner) last = std::max(last, c);
  for (const std::int64_t c : mesh.neighbour) last = std::max(last, c);
  mesh.cell_count = static_cast<std::size_t>(last + 1);
  read_boundary_file(folder, mesh);
  return mesh;
}

mesh::Mesh volume_mesh(PolyMesh& poly, const CellFaces& cells, const std::string& source) {
  mesh::Mesh mesh;
  mesh.dimension = 3;
  VolumeElements elements = volume_elements(poly, cells, volume_cells(poly, cells, source));
  mesh.cells = std::move(elements.cells);
  mesh.polyhedra = std::move(elements.polyhedra);
  int tag = 0;
  for (const BoundaryPatch& p : poly.patches) {
    ++tag;
    if (p.face_count == 0) continue;
    mesh::Patch patch{.name = p.name, .tag = tag, .faces = {}, .nodes = {}};
    for (auto f = static_cast<std::size_t>(p.start_face); f < static_cast<std::size_t>(p.start_face + p.face_count);
         ++f) {
      // Outward (the boundary face's owner): a triangle or a quad as it is, a face with a
      // centre point (foam_polyhedra.hpp) as the triangles from its edges to it.
      const auto begin = static_cast<std::size_t>(poly.faces.offsets[f]);
      const auto n = static_cast<std::size_t>(poly.faces.offsets[f + 1]) - begin;
      const auto point = [&](std::size_t i) { return static_cast<mesh::NodeId>(poly.faces.nodes[begin + i % n]); };
      if (elements.face_centre[f] >= 0) {
        const auto middle = static_cast<mesh::NodeId>(elements.face_centre[f]);
        for (std::size_t i = 0; i < n; ++i) patch.faces.add(mesh::ElementType::tri3, {point(i), point(i + 1), middle});
        continue;
      }
      std::array<mesh::NodeId, 4> nodes{};
      for (std::size_t i = 0; i < n; ++i) nodes[i] = point(i);
      patch.faces.add(n == 3 ? mesh::ElementType::tri3 : mesh::ElementType::quad4, std::span<const mesh::NodeId>(nodes.data(), n));
    }
    mesh.patches.push_back(std::move(patch));
  }
  mesh.points = std::move(poly.points);
  mesh.points.insert(mesh.points.end(), elements.added_points.begin(), elements.added_points.end());
  mesh.derive_node_sets();
  return mesh;
}

std::vector<std::string> other_files(const fs::path& folder) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
    const std::string name = e.path().filename().string();
    if (e.is_regular_file(ec) && name != "points" && name != "points.gz") names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace
}  // namespace foam

FoamMesh read_foam(const fs::path& path) {
  const fs::path folder = foam_mesh_folder(path);
  foam::FoamWriteBackData data;
  data.polymesh = folder;
  foam::PolyMesh poly = foam::read_poly_mesh(folder, data.points);
  const foam::CellFaces cells = foam::cell_faces(poly);
  FoamMesh result;
  if (foam::is_2d(poly)) {
    foam::FlatMesh flat = foam::flatten(poly, cells, folder.string());
    result.mesh = std::move(flat.mesh);
    result.layer = {flat.map.frames[0], flat.map.frames[1]};
    data.map = std::move(flat.map);
  } else {
    data.file_points = poly.points.size();
    result.mesh = foam::volume_mesh(poly, cells, folder.string());
  }
  data.copied_files = foam::other_files(folder);
  result.write_back = foam::make_foam_write_back(std::move(data));
  return result;
}

}  // namespace hotmesh::io
