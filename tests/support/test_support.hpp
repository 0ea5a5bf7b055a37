// hotmesh tests: shared helpers (temporary folders, files, small meshes built in code).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "hotmesh/mesh/mesh.hpp"
#include "sanitizer_build.hpp"

namespace hotmesh::test {

/// A fresh folder under the system temporary directory, removed with its content on exit.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(std::string_view name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

std::filesystem::path data_path(std::string_view name);  ///< tests/data/<name>

/// Whether this test program runs under AddressSanitizer: the numerical comparisons of the
/// larger cases take minutes there, and the sanitizer build runs smaller ones that take the
/// same code paths.
constexpr bool under_sanitizers() { return HOTMESH_TEST_UNDER_ASAN != 0; }
std::string read_text(const std::filesystem::path& path);
void write_text(const std::filesystem::path& path, std::string_view text);

/// The unit square [0,1]^2 as nx x ny quads; patches xmin, xmax, ymin, ymax.
mesh::Mesh unit_square(int nx, int ny);
/// The unit cube [0,1]^3 as n^3 hexes; patches xmin, xmax, ymin, ymax, zmin, zmax.
mesh::Mesh unit_cube(int n);

/// The region between two concentric squares centred at the origin (half sides `inner` and
/// `outer`) as an O-grid of quads: 4 * per_side cells around, `radial` across, each ring
/// `growth` times wider than the one inside it. Patches "inner" and "outer". With
/// layers > 0, extruded to hexes over z in [0, depth] with patches "zmin" and "zmax" too.
mesh::Mesh square_ring(int per_side, int radial, double inner, double outer, int layers = 0, double depth = 0.0,
                         double growth = 1.0);

/// square_ring with its cells split as a hybrid mesh (mesh/split_cells.hpp): the
/// `layer_rings` rings next to the inner square stay quads in 2D and become prisms in 3D (the
/// body's layers), the rings outside become triangles in 2D, and tetrahedra with pyramids
/// against the prisms' sides in 3D (the core).
mesh::Mesh hybrid_ring(int per_side, int radial, double inner, double outer, int layers, double depth, double growth,
                       int layer_rings);

/// A sector of an annulus about the z axis: r in [r0, r1], z in [z0, z1], theta in
/// [0, angle_deg], as nr x nt x nz hexes. Patches "inner" (r0), "outer" (r1), "per_lo"
/// (theta 0), "per_hi" (theta angle), "bottom" (z0), "top" (z1).
mesh::Mesh annular_sector(int nr, int nt, int nz, double r0, double r1, double z0, double z1, double angle_deg);

/// Moves interior nodes (those on no patch) pseudo-randomly by up to `fraction` of the
/// smallest edge length around them, keeping the mesh valid; deterministic.
void jiggle_interior(mesh::Mesh& mesh, double fraction);

/// The points and cells of `mesh` with its nodes numbered at random, by `seed` (as a mesh from
/// an unstructured mesher may come); without patches.
mesh::Mesh shuffled_nodes(const mesh::Mesh& mesh, unsigned seed);

}  // namespace hotmesh::test
