// hotmesh io: reading an OpenFOAM polyMesh folder (see hotmesh/io/foam.hpp). Each of the five
// files is read (gunzipped if it is `name.gz`), its lists checked against the others, then
// the cells built as hexahedra, prisms, pyramids and tetrahedra (3D) or flattened to quads
// and triangles (2D cases).
#include <algorithm>
#include <limits>

#include <fmt/format.h>

#include "foam_2d.hpp"
#include "foam_cells.hpp"
#include "foam_file.hpp"
#include "foam_write_back.hpp"
#include "gzip.hpp"
#include "hotmesh/geometry/input_error.hpp"
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

FoamText read_foam_text(const fs::path& folder, const std::string& name) {
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
  if (text.gzipped) text.content = detail::gunzip(text.content, text.path.string());
  return text;
}

PointsFile read_points(const fs::path& folder, std::vector<geometry::Vec3>& points) {
  FoamText text = read_foam_text(folder, "points");
  PointsFile file;
  FoamCursor in(text.content, text.path.string());
  in.read_header();
  in.skip_space();
  file.list_begin = in.position();
  points = read_vector_list(in, "points");
  file.list_end = in.position();
  if (points.size() > static_cast<std::size_t>(std::numeric_limits<mesh::NodeId>::max())) {
    in.fail_at(file.list_begin, fmt::format("{} points are more than hotmesh can number", points.size()));
  }
  file.name = text.path.filename().string();
  file.gzipped = text.gzipped;
  file.header = in.header();
  file.content = std::move(text.content);
  return file;
}

void read_faces_file(const fs::path& folder, PolyMesh& mesh) {
  const FoamText text = read_foam_text(folder, "faces");
  FoamCursor in(text.content, text.path.string());
  in.read_header();
  mesh.faces = read_faces(in);
  const auto points = static_cast<std::int64_t>(mesh.points.size());
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto begin = mesh.faces.offsets[f], end = mesh.faces.offsets[f + 1];
    if (end - begin < 3) {
      throw InputError::in(in.source(), fmt::format("face {} has {} points (a face needs at least 3)", f, end - begin));
    }
    for (auto i = begin; i < end; ++i) {
      const std::int64_t p = mesh.faces.nodes[static_cast<std::size_t>(i)];
      if (p < 0 || p >= points) {
        throw InputError::in(
            in.source(), fmt::format("face {} refers to point {}, but the points file has {} points (0 to {})", f, p,
                                     points, points - 1));
      }
    }
  }
}

/// Owner (one per face) or neighbour (one per internal face): cell labels >= 0.
std::vector<std::int64_t> read_cells_of_faces(const fs::path& folder, const std::string& name, std::size_t faces) {
  const FoamText text = read_foam_text(folder, name);
  FoamCursor in(text.content, text.path.string());
  in.read_header();
  std::vector<std::int64_t> cells = read_label_list(in, fmt::format("{} cells", name));
  if (name == "owner" ? cells.size() != faces : cells.size() > faces) {
    throw InputError::in(
        in.source(),
        fmt::format("{} cells are listed for {} faces (the faces file): {}", cells.size(), faces,
                    name == "owner" ? "there must be one owner per face" : "at most one neighbour per face"));
  }
  const auto bad = std::find_if(cells.begin(), cells.end(),
                                [](std::int64_t c) { return c < 0 || c >= std::numeric_limits<mesh::CellId>::max(); });
  if (bad != cells.end()) {
    throw InputError::in(in.source(),
                         fmt::format("face {} has {} cell {}, not a cell number", bad - cells.begin(), name, *bad));
  }
  return cells;
}

void read_boundary_file(const fs::path& folder, PolyMesh& mesh) {
  const FoamText text = read_foam_text(folder, "boundary");
  FoamCursor in(text.content, text.path.string());
  in.read_header();
  mesh.patches = read_boundary(in);
  const std::size_t internal = mesh.neighbour.size(), faces = mesh.faces.size();
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
  points_file = read_points(folder, mesh.points);
  read_faces_file(folder, mesh);
  mesh.owner = read_cells_of_faces(folder, "owner", mesh.faces.size());
  mesh.neighbour = read_cells_of_faces(folder, "neighbour", mesh.faces.size());
  for (std::size_t f = 0; f < mesh.neighbour.size(); ++f) {
    if (mesh.neighbour[f] == mesh.owner[f]) {
      throw InputError::in((folder / "neighbour").string(),
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
  const std::vector<FoamCell> elements = volume_cells(poly, cells, source);
  mesh.cells.reserve(elements.size(), 8 * elements.size());
  for (const FoamCell& e : elements) {
    std::array<mesh::NodeId, 8> nodes{};
    std::transform(e.nodes.begin(), e.nodes.end(), nodes.begin(), [](std::int64_t p) { return static_cast<mesh::NodeId>(p); });
    mesh.cells.add(e.type, std::span<const mesh::NodeId>(nodes.data(), static_cast<std::size_t>(mesh::node_count(e.type))));
  }
  int tag = 0;
  for (const BoundaryPatch& p : poly.patches) {
    ++tag;
    if (p.face_count == 0) continue;
    mesh::Patch patch{.name = p.name, .tag = tag, .faces = {}, .nodes = {}};
    for (auto f = static_cast<std::size_t>(p.start_face); f < static_cast<std::size_t>(p.start_face + p.face_count);
         ++f) {
      // A face of a cell read above: a triangle or a quad, outward (the boundary face's owner).
      const auto begin = static_cast<std::size_t>(poly.faces.offsets[f]);
      const auto n = static_cast<std::size_t>(poly.faces.offsets[f + 1]) - begin;
      std::array<mesh::NodeId, 4> nodes{};
      for (std::size_t i = 0; i < n; ++i) nodes[i] = static_cast<mesh::NodeId>(poly.faces.nodes[begin + i]);
      patch.faces.add(n == 3 ? mesh::ElementType::tri3 : mesh::ElementType::quad4, std::span<const mesh::NodeId>(nodes.data(), n));
    }
    mesh.patches.push_back(std::move(patch));
  }
  mesh.points = std::move(poly.points);
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
    data.map = std::move(flat.map);
  } else {
    result.mesh = foam::volume_mesh(poly, cells, folder.string());
  }
  data.copied_files = foam::other_files(folder);
  result.write_back = foam::make_foam_write_back(std::move(data));
  return result;
}

}  // namespace hotmesh::io
