// hotmesh app: CAD faces, edges and axes as JSON (see cad_json.hpp).
#include "fits/cad_json.hpp"

namespace hotmesh::app {

nlohmann::json vec3_json(const geometry::Vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

nlohmann::json axis_json(const geometry::Axis& axis) {
  return {{"origin", vec3_json(axis.origin())}, {"direction", vec3_json(axis.direction())}};
}

nlohmann::json face_json(const geometry::FaceInfo& face) {
  nlohmann::json axis = nullptr;
  if (face.axis) {
    axis = axis_json(*face.axis);
    axis["source"] = geometry::to_string(face.axis_source);
  }
  return {{"id", face.id},
          {"name", face.name},
          {"kind", geometry::to_string(face.kind)},
          {"axis", axis},
          {"bounds", {{"min", vec3_json(face.bounds.min)}, {"max", vec3_json(face.bounds.max)}}}};
}

nlohmann::json faces_json(const geometry::CadModel& model) {
  nlohmann::json faces = nlohmann::json::array();
  for (const geometry::FaceInfo& face : model.faces()) faces.push_back(face_json(face));
  return faces;
}

nlohmann::json edge_json(const geometry::EdgeInfo& edge) {
  return {{"id", edge.id},
          {"kind", geometry::to_string(edge.kind)},
          {"start", vec3_json(edge.start)},
          {"end", vec3_json(edge.end)},
          {"length", edge.length}};
}

nlohmann::json edges_json(const geometry::CadModel& model) {
  nlohmann::json edges = nlohmann::json::array();
  for (const geometry::EdgeInfo& edge : model.edges()) edges.push_back(edge_json(edge));
  return edges;
}

}  // namespace hotmesh::app
