// hotmesh sample stator_well: the FEM deflection tables of the severe case (the paper's §6.2)
// and the case files that use them.
//
// The FEM model is axisymmetric, like the paper's SC03 model: its boundary nodes lie on the
// metal walls' meridional curves, at every corner and junction of the profile and in between
// at most `fem_spacing` apart (uniform in arc length per curve), so they are coarser than the
// CFD wall nodes and do not coincide with them. A node shared by two walls (a corner) has one
// id and one deflection in both tables. The deflections (dz, dr):
//   rotor, upper component (rim_up, disc_up_upper, upper half of joint, rim_down):
//       dz = axial_shift,  dr = rotor_growth * r / r_hub
//   rotor, lower component (lower half of joint, disc_up_lower, disc_base):
//       dz = axial_shift,  dr = rotor_growth * r / r_hub + joint_jump
//   downstream disc (disc_down): the lower component's jump fades out up the disc face,
//       dr = rotor_growth * r / r_hub + joint_jump * w(r), w = 1 below 330 mm, 0 above 400 mm
//       (a smoothstep between)
//   stator (stator_front, fins, stator_rear): dz = 0, dr = stator_growth * r / r_hub
// so the disc base runs axially by axial_shift under the fins while the seal clearance closes
// by (rotor_growth * r_drum - stator_growth * r_tip) / r_hub + joint_jump (about 60 % of it),
// and the joint's end (B upper, C lower, 1 mm apart) opens a jump of joint_jump in dr.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "stator_well.hpp"

namespace hotmesh::samples::stator_well {

struct SevereCase {
  double axial_shift = 1.0e-3;     ///< m, the whole rotor, downstream
  double rotor_growth = 0.5e-3;    ///< m, radial growth of the rotor at the hub radius (0.42 m)
  double stator_growth = 0.25e-3;  ///< m, radial growth of the stator at the hub radius
  double joint_jump = 0.4e-3;      ///< m, the lower disc component's extra radial motion
  double fem_spacing = 5.0e-3;     ///< m, largest distance between FEM nodes along a wall
};

/// (dz, dr) of a point (z, r) of a patch's wall.
Vec2 deflection(Patch patch, Vec2 zr, const SevereCase& severe);

struct FemNode {
  std::int64_t id = 0;
  Vec2 zr;   ///< position (z, r)
  Vec2 dzr;  ///< deflection (dz, dr)
};

struct FemTable {
  Patch patch;
  std::vector<FemNode> nodes;  ///< along the patch's wall
};

/// The metal patches that carry a table, in Patch order.
std::vector<Patch> table_patches();
/// One table per metal patch, in table_patches() order.
std::vector<FemTable> fem_tables(const std::vector<ProfileCurve>& loop, const SevereCase& severe = {});
/// "<patch>.csv"
std::string table_file(Patch patch);
/// The table as CSV: comment lines, then "id,r,z,dr,dz" and one row per node.
std::string table_csv(const FemTable& table, const SevereCase& severe);

/// The role of a patch in the case files: "fixed", "passive", "prescribed", "sliding" or
/// "periodic"; the disc faces and the disc base slide only with `sliding`.
const char* role(Patch patch, bool sliding);

/// What the tables do to the two small gaps (metres): the seal clearance between the fin tips and
/// the disc base, and the joint's gap between B and C, before and after.
struct GapChanges {
  double clearance_before = 0.0, clearance_after = 0.0;
  double joint_before = 0.0, joint_after = 0.0;
};
GapChanges gap_changes(const std::vector<FemTable>& tables);

/// "case_<label>.yaml", or "case_<label>_nosliding.yaml".
std::string case_file_name(const std::string& label, bool sliding);
/// The case file of the sample, for the mesh, CAD file and tables written beside it: sliding
/// on the disc faces and the disc base (the paper's "sliding option on"), or every metal wall
/// prescribed (`sliding` false).
std::string case_file(const std::vector<ProfileCurve>& loop, const std::string& label, bool sliding);

/// "case_<label>_<format>.yaml" (format "cgns" or "foam").
std::string engine_case_file_name(const std::string& label, const std::string& format);
/// The sliding case file on the mesh `mesh` (kCgnsFile or kFoamCase) instead of the .msh file:
/// the same roles and tables.
std::string engine_case_file(const std::vector<ProfileCurve>& loop, const std::string& label, const std::string& format,
                             const std::string& mesh);

}  // namespace hotmesh::samples::stator_well
