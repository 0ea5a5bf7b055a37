// hotmesh setup: meridional or surface, for CAD faces (see faces_mode.hpp).
#include "hotmesh/setup/faces_mode.hpp"

#include <utility>

#include "hotmesh/core/input_error.hpp"

namespace hotmesh::setup {

FacesMode choose_faces_mode(const geometry::CadModel& cad, std::span<const int> faces,
                            const std::optional<geometry::Axis>& axis, io::WallMode asked) {
  if (asked == io::WallMode::surface) return {};
  try {
    return {io::WallMode::meridional, cad.meridional_profiles(faces, {.axis = axis}), {}};
  } catch (const InputError& e) {  // no common axis, a face not rotational about it, ...
    if (asked == io::WallMode::meridional) throw;
    std::string reason = e.what();
    const std::string file = cad.path().string() + ": ";
    if (reason.starts_with(file)) reason.erase(0, file.size());
    return {io::WallMode::surface, {}, std::move(reason)};
  }
}

}  // namespace hotmesh::setup
