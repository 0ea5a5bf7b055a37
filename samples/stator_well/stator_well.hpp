// hotmesh sample stator_well: the turbine stator well of the paper's section 6 (Figs. 11-17),
// as a library shared by the generator (make_stator_well), its tests and the benchmark.
//
// The fluid domain is a 3.6 degree sector of the interstage cavity of a HP turbine, engine axis
// = z, r radial, in metres. Its meridional profile (the boundary loop of the (z, r) plane) is
// made of lines and B-splines; revolved about the axis it is the CAD model, swept in theta it is
// the hex mesh. Layout of the profile, the patches and their roles: README.md beside this file.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "block_mesh.hpp"
#include "hotmesh/mesh/mesh.hpp"
#include "hotmesh/geometry/revolved_export.hpp"

namespace hotmesh::samples::stator_well {

/// The sector angle, as in the paper's model (100 sectors).
inline constexpr double kSectorDegrees = 3.6;
/// The size of the committed sample and of the tests, in hex cells.
inline constexpr std::int64_t kSmallCells = 18000;
/// The files the generator writes besides the tables and case files.
inline constexpr const char* kMeshFile = "stator_well.msh";
inline constexpr const char* kCadFile = "stator_well.step";
inline constexpr const char* kCgnsFile = "stator_well.cgns";   ///< --engine-formats
inline constexpr const char* kFoamCase = "stator_well_foam";   ///< --engine-formats: an OpenFOAM case folder

/// Mesh patches, in the order of their tags (tag = index + 1); roles as in case_small.yaml.
enum class Patch {
  inlet,          ///< main annulus inlet (passive)
  outlet,         ///< main annulus outlet (passive)
  casing,         ///< outer casing of the annulus (fixed)
  blade,          ///< the stator vane's leading and trailing faces (fixed)
  stator_outer,   ///< the stator platform's gas-path surface beside the vane (passive)
  stator_front,   ///< stator: front lip, its underside, fillet, diaphragm front face (prescribed)
  fins,           ///< stator: the seal land and its three fins (prescribed)
  stator_rear,    ///< stator: diaphragm rear face, fillet, rear lip underside and lip (prescribed)
  rim_up,         ///< upstream rotor: blade platform and rim lip face (prescribed)
  disc_up_upper,  ///< upstream disc, upper component: lip underside, fillet, face (sliding)
  joint,          ///< the radial gap between the upstream disc's components (prescribed)
  disc_up_lower,  ///< upstream disc, lower component: face below the joint (sliding)
  disc_base,      ///< the drum joining the discs, under the seal fins (sliding)
  disc_down,      ///< downstream disc: face, fillet, lip underside (sliding)
  rim_down,       ///< downstream rotor: rim lip face and blade platform (prescribed)
  per_lo,         ///< periodic face at theta = 0
  per_hi,         ///< periodic face at theta = 3.6 degrees
};
inline constexpr int kPatchCount = 17;
std::string_view name(Patch patch);

/// One piece of the meridional profile, in the direction of the loop.
struct ProfileCurve {
  std::string name;      ///< CAD face name, "<patch>.<part>"
  Patch patch;
  BSplineCurve2d curve;  ///< (z, r) in metres
};

/// The closed boundary loop of the fluid's meridional section, counter-clockwise in (z, r),
/// starting at the inlet's casing corner.
std::vector<ProfileCurve> profile();

/// The CAD faces: indices into the loop in face order (face id = position + 1). Faces are
/// grouped by patch, in Patch order, and run along each patch in increasing z.
std::vector<int> cad_face_order(const std::vector<ProfileCurve>& loop);
/// The CAD face ids of a patch, ascending.
std::vector<int> cad_faces(const std::vector<ProfileCurve>& loop, Patch patch);

/// The profile revolved about z by the sector angle, one face per curve in CAD face order.
geometry::RevolvedModel cad_model(const std::vector<ProfileCurve>& loop);

/// The multi-block layout of the meridional section (stator_well_blocks.cpp).
BlockLayout block_layout(const std::vector<ProfileCurve>& loop);
/// The spacing field at refinement 1 (metres).
SpacingField spacing_field();

/// A mesh size: the refinement of the meridional blocks and the cells in theta.
struct Size {
  double refinement = 1.0;
  int theta_cells = 0;
  std::int64_t quads = 0;  ///< of the meridional section
  std::int64_t cells = 0;  ///< hexahedra: quads * theta_cells
  std::int64_t nodes = 0;
};
/// The size at refinement s: theta cells = max(3, round(3.6 s)).
Size size_at(const BlockMesher& mesher, double refinement);
/// The refinement whose cell count is nearest `cells` (bisection over s).
Size size_for_cells(const BlockMesher& mesher, std::int64_t cells);

/// The 3D sector: the meridional quads swept in theta over the sector angle, hexes numbered
/// theta layer by layer, patches tagged in Patch order (walls by their profile curve's patch,
/// per_lo at theta = 0 and per_hi at the sector angle), one cell group "fluid". Boundary faces
/// point out of the fluid.
mesh::Mesh sector_mesh(const QuadMesh& section, const std::vector<ProfileCurve>& loop, int theta_cells);

/// (r, z) of a point given as (z, r): the meridional convention of hotmesh's geometry.
inline Vec2 to_rz(const Vec2& zr) { return {zr.y, zr.x}; }

/// Writes the sector as a structured multi-block CGNS file (HDF5): one zone per block of
/// `section` (i, j the block's, k along theta), GridConnectivity1to1 between blocks sharing a
/// side, BCs as vertex point ranges whose FamilyName is the patch (also the BC's name, with
/// _2, _3 appended where a zone has more than one of a patch). `sector` is
/// sector_mesh(section, loop, theta_cells). Throws std::runtime_error with the library's message.
void write_sector_cgns(const std::filesystem::path& path, const QuadMesh& section, const mesh::Mesh& sector,
                       const std::vector<ProfileCurve>& loop, int theta_cells);

/// Writes the sector as an OpenFOAM case: `folder`/constant/polyMesh (hotmesh's polyMesh
/// writer; per_lo, per_hi, inlet and outlet of type patch, the others wall) and the system/
/// files checkMesh reads.
void write_sector_foam(const std::filesystem::path& folder, const mesh::Mesh& sector, bool binary);

}  // namespace hotmesh::samples::stator_well
