// hotmesh setup: how CAD faces are taken by `hotmesh check` and `hotmesh serve`, chosen as hotmesh
// deform chooses for a case's wall (io::WallMode, case_setup.hpp): as a surface of revolution,
// through their meridional curve (eq. 20), only when every face turns about one axis (the axis
// given, else one the faces share: a plane across it counts, a plane along it does not); else
// as the faces themselves (a surface wall). One rotational face among planes (a fillet on a
// step) therefore no longer makes its axis everyone's.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/io/case_file.hpp"

namespace hotmesh::setup {

struct FacesMode {
  io::WallMode mode = io::WallMode::surface;        ///< meridional or surface, never automatic
  std::vector<geometry::MeridionalCurve> profiles;  ///< meridional: one per separate profile, about one axis
  /// Surface chosen by `automatic`: why the faces are no surface of revolution (the kernel's
  /// message naming the face, without the file's name).
  std::string reason;
};

/// The mode of `faces` of `cad`: `asked` unless it is `automatic`, which chooses meridional when
/// the faces form surfaces of revolution about `axis` (or, without it, about the axis the faces
/// with one share; CadModel::meridional_profiles) and surface otherwise. Throws
/// hotmesh::InputError naming the face at fault when meridional is asked and impossible.
FacesMode choose_faces_mode(const geometry::CadModel& cad, std::span<const int> faces,
                            const std::optional<geometry::Axis>& axis, io::WallMode asked);

}  // namespace hotmesh::setup
