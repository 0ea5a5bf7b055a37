// hotmesh io: VTK XML unstructured grids (.vtu) and poly data (.vtp) for ParaView, binary
// appended raw data with UInt64 headers. Point and cell arrays are passed by the caller (displacement, node role,
// scaled Jacobian, inverted flag, ...).
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "hotmesh/mesh/mesh.hpp"
#include "hotmesh/mesh/solver_quality.hpp"

namespace hotmesh::io {

/// One named data array: `components` values per point (or cell), stored interleaved.
struct VtuArray {
  std::string name;
  int components = 1;
  std::variant<std::vector<double>, std::vector<std::int32_t>, std::vector<std::int64_t>, std::vector<std::uint8_t>>
      values;
};

struct VtuFields {
  std::vector<VtuArray> point_data;
  std::vector<VtuArray> cell_data;
};

/// VTK cell type number of a hotmesh element type (VTK_QUAD = 9, VTK_HEXAHEDRON = 12, ...).
std::uint8_t vtk_cell_type(mesh::ElementType type);

/// Cell quality (scaled_jacobian, inverted, and the flow solver's non_orthogonality in
/// degrees, skewness, volume_ratio and aspect_ratio of mesh::SolverQuality) and, per node, the
/// 1-based index of the first patch it lies on (0 inside): the arrays every VTU from hotmesh
/// carries. `layer`: what a 2D mesh's cells stand for (io::LoadedMesh::layer).
VtuFields quality_fields(const mesh::Mesh& mesh, std::span<const geometry::Vec3> points,
                         const mesh::Extrusion& layer = {});
/// The same with the solver's measures already made.
VtuFields quality_fields(const mesh::Mesh& mesh, std::span<const geometry::Vec3> points,
                         const mesh::SolverQuality& solver);

/// Writes the cells of `mesh` at coordinates `points` (mesh.points, or a deformed copy).
/// Throws std::invalid_argument if an array has the wrong length.
void write_vtu(std::ostream& out, const mesh::Mesh& mesh, std::span<const geometry::Vec3> points,
               const VtuFields& fields);
void write_vtu(const std::filesystem::path& path, const mesh::Mesh& mesh,
               std::span<const geometry::Vec3> points, const VtuFields& fields);

/// Vertices, polylines and polygons through points, with one value per point in each point
/// array and one per cell (vertices first, then lines, then polygons) in each cell array: a VTK
/// PolyData (.vtp), e.g. the deflected walls of a case or FEM nodes as vertices.
struct PolyData {
  std::vector<geometry::Vec3> points;
  std::vector<std::vector<std::int64_t>> vertices;  ///< (poly)vertices: indices into points
  std::vector<std::vector<std::int64_t>> lines;     ///< polylines: indices into points
  std::vector<std::vector<std::int64_t>> polygons;  ///< polygons: indices into points
  std::vector<VtuArray> point_data;
  std::vector<VtuArray> cell_data;
};

/// Writes `data` as a VTK XML PolyData file. Throws std::invalid_argument for an index out of
/// range or an array of the wrong length.
void write_vtp(std::ostream& out, const PolyData& data);
void write_vtp(const std::filesystem::path& path, const PolyData& data);

}  // namespace hotmesh::io
