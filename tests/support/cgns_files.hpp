// hotmesh tests: small CGNS files written with the CGNS library, as inputs to the reader.
// Each writer documents the mesh it makes and what hotmesh should make of it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace hotmesh::test {

/// 2D unstructured, 3 x 2 quads on [0,3] x [0,2] (node (i,j) = i + 4 j + 1), physical dimension 2.
/// Section "Cells": MIXED of the 6 QUAD_4 (elements 1-6). Section "Bottom": BAR_2 at y = 0
/// (7-9), named by BC "bottom" (ElementRange as PointRange at EdgeCenter). Section "TopEdges":
/// BAR_2 at y = 2 (10-12), named by no BC. BCs "left" (x = 0) and "right" (x = 3) by PointList
/// at vertices. A FlowSolution "Flow" with a vertex field "Pressure".
/// Patches: bottom 3 faces, left 2, right 2, TopEdges 3.
void write_unstructured_2d(const std::filesystem::path& path);

/// 3D unstructured, 2 x 2 x 2 hexes on [0,2]^3, RealDouble, in one MIXED section of 8
/// HEXA_8 and the 4 QUAD_4 faces at z = 0 (elements 9-12). BC "floor": ElementList 9-12.
/// BCs "xmin", "xmax", "ymin", "ymax" by PointList with FamilyName "Casing"; BC "top" (z = 2)
/// by PointList. Patches: floor 4, Casing 16, top 4.
void write_unstructured_3d(const std::filesystem::path& path);

/// 2D structured, two zones of 3 x 2 cells, RealSingle. "A": i along x, [0,1] x [0,1].
/// "B": left-handed, i along y and j along x, [1,2] x [0,1]. Joined by GridConnectivity1to1
/// at x = 1 (transform [2, 1]). BCs: A "inlet" (x = 0, vertex range), A "wall_a" and B
/// "wall_b" (y = 0) both in family "Walls", A "top" (y = 1, EdgeCenter range) and B "top"
/// (y = 1, vertex range), B "outlet" (x = 2). FlowSolution "Flow" with "Pressure" in each zone.
/// Mesh: 21 nodes, 12 cells; patches inlet 2, Walls 6, top 6, outlet 2.
/// With `wrong_interface`, A's side of the interface maps A's j = 1..3 to B's i = 3..1 (a
/// transform the library accepts, joining nodes that are apart).
void write_structured_2d(const std::filesystem::path& path, bool wrong_interface = false);

/// 3D structured, two zones of 2 x 2 x 2 cells: "A" on [0,1]^3, "B" on [1,2] x [0,1]^2,
/// sharing the face x = 1 point for point with no connectivity records. BCs by vertex point
/// ranges: A "xmin", B "xmax", and in both zones "ymin", "ymax", "zmin", "zmax".
/// Mesh: 45 nodes, 16 cells; patches xmin 4, xmax 4, ymin 8, ymax 8, zmin 8, zmax 8.
void write_structured_3d(const std::filesystem::path& path);

/// 2D unstructured, two zones of 3 x 2 quads: "Left" on [0,3] x [0,2], "Right" on [3,6] x
/// [0,2]. With `connectivity`, joined by GridConnectivity Abutting1to1 PointList /
/// PointListDonor at x = 3 (both ways); without, Right's interface nodes are 1e-7 off Left's
/// and only coincidence joins them. BCs by PointList: "left" (x = 0), "right" (x = 6), and
/// "bottom" / "top" of each zone in family "Walls".
/// Mesh: 21 nodes, 12 cells; patches left 2, Walls 12, right 2.
void write_unstructured_two_zones(const std::filesystem::path& path, bool connectivity);

/// 2D structured, one zone of 3 x 2 cells on [0,1] x [0,1], periodic in y: 1-to-1
/// connections "per_lo" (j = 1 to j = 3) and "per_hi" (back) of the zone with itself, each with
/// a periodic translation. BCs "inlet" (x = 0) and "outlet" (x = 1).
/// Mesh: 12 nodes (none merged), 6 cells; patches inlet 2, outlet 2, per_lo 3, per_hi 3.
void write_structured_periodic_2d(const std::filesystem::path& path);

/// Variants for error cases.
void write_with_quadratic_triangles(const std::filesystem::path& path);  ///< 2D, section "Tris" of 2 TRI_6
void write_bc_without_faces(const std::filesystem::path& path); ///< 2D, BC "lonely" of 1 node

/// Rewrites the file as the CGNS library before 3.4 wrote it (CGNS 3.1 and older, SU2's
/// mesh_bend_coarse.cgns and the files of many meshers): CGNSLibraryVersion 3.1, and no
/// ElementStartOffset in any section (a MIXED section's connectivity is the same without it).
void make_legacy(const std::filesystem::path& path);

/// Replaces node `node` of the file (a path from its root) by a link to the node of the same
/// path in file `target`, as CGNS files that share a grid do.
void link_node(const std::filesystem::path& path, const std::string& node, const std::filesystem::path& target);

/// Replaces the data of node `node` of a CGNS file (a path from its root,
/// "/Base/Fluid/Cells/ElementRange") with `values`, stored as I4 integers of `dimensions`
/// (by default one, of values.size() entries): a file's arrays edited in place, as someone
/// crafting a damaged file would, past the checks the library makes when writing.
void overwrite_integers(const std::filesystem::path& path, const std::string& node, const std::vector<int>& values,
                        std::vector<long long> dimensions = {});

/// The coordinates of every zone of base 1, zone after zone, as doubles (CoordinateX, Y[, Z]
/// interleaved per node, 0 for a missing Z), and the data type names of each coordinate.
struct ZoneCoordinates {
  std::vector<double> xyz;
  std::vector<std::string> types;
};
std::vector<ZoneCoordinates> read_zone_coordinates(const std::filesystem::path& path);
/// Field `field` of solution `solution` of zone `zone` (1-based), as doubles.
std::vector<double> read_field(const std::filesystem::path& path, int zone, int solution, const std::string& field);

}  // namespace hotmesh::test
