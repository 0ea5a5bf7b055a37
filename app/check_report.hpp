// hotmesh app: the result of `hotmesh check` (distance of each mapped patch's nodes to its
// reference shape) and its three forms: text for people, JSON for scripts, JUnit XML for CI
// systems (one test case per patch; a patch above the tolerance fails naming its worst node).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hotmesh/geometry/vec3.hpp"

namespace hotmesh::app {

struct PatchCheck {
  std::string patch;
  std::string reference;      ///< what the nodes were measured against
  std::size_t nodes = 0;
  double max_distance = 0.0;
  double mean_distance = 0.0;
  std::int64_t worst_node = 0;  ///< node id in the mesh file
  geometry::Vec3 worst_point;
  double seconds = 0.0;
  bool passed = true;         ///< max_distance <= tolerance
};

struct CheckResult {
  std::string mesh;
  std::string cad;  ///< empty without CAD
  double tolerance = 0.0;
  std::string unit;
  std::vector<PatchCheck> patches;

  bool passed() const;
};

std::string check_text(const CheckResult& result);
std::string check_json(const CheckResult& result);
std::string check_junit(const CheckResult& result);

}  // namespace hotmesh::app
