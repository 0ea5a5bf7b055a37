// hotmesh app: CAD faces, edges and axes as JSON, the same for `hotmesh cad --json`, summary.json and
// the service's answers.
#pragma once

#include <nlohmann/json.hpp>

#include "hotmesh/geometry/cad_model.hpp"

namespace hotmesh::app {

nlohmann::json vec3_json(const geometry::Vec3& v);  ///< [x, y, z]
/// {"origin": [x, y, z], "direction": [dx, dy, dz]}
nlohmann::json axis_json(const geometry::Axis& axis);
/// {"id", "name", "kind", "axis": {origin, direction, source} or null, "bounds": {min, max}}
nlohmann::json face_json(const geometry::FaceInfo& face);
/// [face_json, ...] in id order.
nlohmann::json faces_json(const geometry::CadModel& model);
/// {"id", "kind", "start": [x, y, z], "end": [x, y, z], "length"}
nlohmann::json edge_json(const geometry::EdgeInfo& edge);
/// [edge_json, ...] in id order.
nlohmann::json edges_json(const geometry::CadModel& model);

}  // namespace hotmesh::app
