// hotmesh io: VTK XML UnstructuredGrid and PolyData writers (binary appended, raw encoding,
// UInt64 headers).
#include "hotmesh/io/vtu.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <ostream>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/io/atomic_file.hpp"

namespace hotmesh::io {
namespace {

static_assert(std::endian::native == std::endian::little, "the VTU writer declares LittleEndian data");

/// A block of the appended section: its XML declaration and its raw bytes.
struct Block {
  std::string xml_open;  // "<DataArray type=... format="appended" offset="
  const char* data = nullptr;
  std::uint64_t bytes = 0;
};

template <class T>
Block block(const std::string& type, const std::string& name, int components, const std::vector<T>& v) {
  Block b;
  b.xml_open = fmt::format(R"(<DataArray type="{}" Name="{}" NumberOfComponents="{}" format="appended" offset=")",
                           type, name, components);
  b.data = reinterpret_cast<const char*>(v.data());
  b.bytes = v.size() * sizeof(T);
  return b;
}

Block array_block(const VtuArray& a, std::size_t count, const char* where) {
  const auto expected = count * static_cast<std::size_t>(a.components);
  return std::visit(
      [&](const auto& v) {
        using T = typename std::decay_t<decltype(v)>::value_type;
        if (v.size() != expected) {
          throw std::invalid_argument(fmt::format("{} array '{}' has {} values, expected {}", where, a.name,
                                                  v.size(), expected));
        }
        const char* type = std::is_same_v<T, double>         ? "Float64"
                           : std::is_same_v<T, std::int32_t> ? "Int32"
                           : std::is_same_v<T, std::int64_t> ? "Int64"
                                                             : "UInt8";
        return block(type, a.name, a.components, v);
      },
      a.values);
}

/// The declarations of a VTK XML file's arrays, in order, and their bytes in one appended
/// section at the end.
class AppendedArrays {
 public:
  explicit AppendedArrays(std::ostream& out) : out_(out) {}
  void declare(const Block& b) {
    out_ << "        " << b.xml_open << offset_ << "\"/>\n";
    offset_ += sizeof(std::uint64_t) + b.bytes;
    order_.push_back(&b);
  }
  /// After the closing tag of the data set: the appended section and the file's end.
  void finish() {
    out_ << "  <AppendedData encoding=\"raw\">\n   _";
    for (const Block* b : order_) {
      out_.write(reinterpret_cast<const char*>(&b->bytes), sizeof(b->bytes));
      out_.write(b->data, static_cast<std::streamsize>(b->bytes));
    }
    out_ << "\n  </AppendedData>\n</VTKFile>\n";
  }

 private:
  std::ostream& out_;
  std::vector<const Block*> order_;  // appended data follows declaration order
  std::uint64_t offset_ = 0;
};

std::vector<double> flat_coordinates(std::span<const geometry::Vec3> points) {
  std::vector<double> coordinates(3 * points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    coordinates[3 * i] = points[i].x;
    coordinates[3 * i + 1] = points[i].y;
    coordinates[3 * i + 2] = points[i].z;
  }
  return coordinates;
}

/// VTK's cell arrays of `cells` (lists of point indices): connectivity and end offsets.
struct CellArrays {
  std::vector<std::int64_t> connectivity;
  std::vector<std::int64_t> offsets;
};
CellArrays cell_arrays(const std::vector<std::vector<std::int64_t>>& cells) {
  CellArrays a;
  for (const auto& c : cells) {
    a.connectivity.insert(a.connectivity.end(), c.begin(), c.end());
    a.offsets.push_back(static_cast<std::int64_t>(a.connectivity.size()));
  }
  return a;
}

}  // namespace

std::uint8_t vtk_cell_type(mesh::ElementType type) {
  using mesh::ElementType;
  switch (type) {
    case ElementType::line2: return 3;
    case ElementType::tri3: return 5;
    case ElementType::quad4: return 9;
    case ElementType::tet4: return 10;
    case ElementType::hex8: return 12;
    case ElementType::wedge6: return 13;
    case ElementType::pyramid5: return 14;
  }
  return 0;
}

void write_vtu(std::ostream& out, const mesh::Mesh& mesh, std::span<const geometry::Vec3> points,
               const VtuFields& fields) {
  if (points.size() != mesh.node_count()) throw std::invalid_argument("write_vtu: one point per mesh node expected");
  const auto& cells = mesh.cells;
  const std::vector<double> coordinates = flat_coordinates(points);
  std::vector<std::int64_t> connectivity(cells.all_nodes().begin(), cells.all_nodes().end());
  std::vector<std::int64_t> offsets(cells.size());
  std::vector<std::uint8_t> types(cells.size());
  std::int64_t end = 0;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    end += static_cast<std::int64_t>(cells.nodes(c).size());
    offsets[c] = end;
    types[c] = vtk_cell_type(cells.type(c));
  }

  std::vector<Block> point_blocks, cell_blocks;
  for (const auto& a : fields.point_data) point_blocks.push_back(array_block(a, points.size(), "point"));
  for (const auto& a : fields.cell_data) cell_blocks.push_back(array_block(a, cells.size(), "cell"));
  const Block points_block = block("Float64", "Points", 3, coordinates);
  const Block cell_arrays[] = {block("Int64", "connectivity", 1, connectivity), block("Int64", "offsets", 1, offsets),
                               block("UInt8", "types", 1, types)};

  AppendedArrays appended(out);
  const auto declare = [&](const Block& b) { appended.declare(b); };

  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
         "  <UnstructuredGrid>\n";
  out << "    <Piece NumberOfPoints=\"" << points.size() << "\" NumberOfCells=\"" << cells.size() << "\">\n";
  out << "      <PointData>\n";
  for (const auto& b : point_blocks) declare(b);
  out << "      </PointData>\n      <CellData>\n";
  for (const auto& b : cell_blocks) declare(b);
  out << "      </CellData>\n      <Points>\n";
  declare(points_block);
  out << "      </Points>\n      <Cells>\n";
  for (const auto& b : cell_arrays) declare(b);
  out << "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n";
  appended.finish();
}

void write_vtp(std::ostream& out, const PolyData& data) {
  const std::size_t cells = data.vertices.size() + data.lines.size() + data.polygons.size();
  for (const auto* kind : {&data.vertices, &data.lines, &data.polygons}) {
    for (const auto& c : *kind) {
      if (std::any_of(c.begin(), c.end(), [&](std::int64_t i) { return i < 0 || std::cmp_greater_equal(i, data.points.size()); })) {
        throw std::invalid_argument("write_vtp: point index out of range");
      }
    }
  }
  const std::vector<double> coordinates = flat_coordinates(data.points);
  const CellArrays vertices = cell_arrays(data.vertices);
  const CellArrays lines = cell_arrays(data.lines);
  const CellArrays polygons = cell_arrays(data.polygons);
  std::vector<Block> point_blocks, cell_blocks;
  for (const auto& a : data.point_data) point_blocks.push_back(array_block(a, data.points.size(), "point"));
  for (const auto& a : data.cell_data) cell_blocks.push_back(array_block(a, cells, "cell"));
  const Block points_block = block("Float64", "Points", 3, coordinates);
  const auto connectivity = [](const CellArrays& a) {
    return std::array<Block, 2>{block("Int64", "connectivity", 1, a.connectivity), block("Int64", "offsets", 1, a.offsets)};
  };
  const std::array<Block, 2> vertex_blocks = connectivity(vertices);
  const std::array<Block, 2> line_blocks = connectivity(lines);
  const std::array<Block, 2> polygon_blocks = connectivity(polygons);

  AppendedArrays appended(out);
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
         "  <PolyData>\n";
  out << "    <Piece NumberOfPoints=\"" << data.points.size() << "\" NumberOfVerts=\"" << data.vertices.size()
      << "\" NumberOfLines=\"" << data.lines.size() << "\" NumberOfStrips=\"0\" NumberOfPolys=\""
      << data.polygons.size() << "\">\n";
  out << "      <PointData>\n";
  for (const auto& b : point_blocks) appended.declare(b);
  out << "      </PointData>\n      <CellData>\n";
  for (const auto& b : cell_blocks) appended.declare(b);
  out << "      </CellData>\n      <Points>\n";
  appended.declare(points_block);
  out << "      </Points>\n      <Verts>\n";
  for (const auto& b : vertex_blocks) appended.declare(b);
  out << "      </Verts>\n      <Lines>\n";
  for (const auto& b : line_blocks) appended.declare(b);
  out << "      </Lines>\n      <Polys>\n";
  for (const auto& b : polygon_blocks) appended.declare(b);
  out << "      </Polys>\n    </Piece>\n  </PolyData>\n";
  appended.finish();
}

void write_vtp(const std::filesystem::path& path, const PolyData& data) {
  AtomicFile file(path);
  write_vtp(file.stream(), data);
  file.commit();
}

VtuFields quality_fields(const mesh::Mesh& mesh, std::span<const geometry::Vec3> points, const mesh::Extrusion& layer) {
  return quality_fields(mesh, points, mesh::solver_quality(mesh, points, layer));
}

VtuFields quality_fields(const mesh::Mesh& mesh, std::span<const geometry::Vec3> points,
                         const mesh::SolverQuality& solver) {
  VtuFields fields;
  std::vector<double> quality = mesh::scaled_jacobians(mesh.cells, points);
  std::vector<std::uint8_t> inverted(quality.size());
  std::transform(quality.begin(), quality.end(), inverted.begin(), [](double q) { return q <= 0.0 ? 1 : 0; });
  fields.cell_data.push_back({"scaled_jacobian", 1, std::move(quality)});
  fields.cell_data.push_back({"inverted", 1, std::move(inverted)});
  fields.cell_data.push_back({"non_orthogonality", 1, solver.non_orthogonality});
  fields.cell_data.push_back({"skewness", 1, solver.skewness});
  fields.cell_data.push_back({"volume_ratio", 1, solver.volume_ratio});
  fields.cell_data.push_back({"aspect_ratio", 1, solver.aspect_ratio});
  std::vector<std::int32_t> patch(mesh.node_count(), 0);
  for (std::size_t p = mesh.patches.size(); p-- > 0;) {
    for (mesh::NodeId n : mesh.patches[p].nodes) patch[static_cast<std::size_t>(n)] = static_cast<std::int32_t>(p + 1);
  }
  fields.point_data.push_back({"patch", 1, std::move(patch)});
  return fields;
}

void write_vtu(const std::filesystem::path& path, const mesh::Mesh& mesh, std::span<const geometry::Vec3> points,
               const VtuFields& fields) {
  AtomicFile file(path);
  write_vtu(file.stream(), mesh, points, fields);
  file.commit();
}

}  // namespace hotmesh::io
