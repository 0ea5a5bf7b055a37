// hotmesh api: the result of `hotmesh check` (distance of each mapped patch's nodes to its
// reference shape, and the two-sided distance of its faces) and its three forms: text for people, JSON for scripts, JUnit XML for CI
// systems (one test case per patch; a patch above the tolerance fails naming its worst node).
// A check that cannot be made (bad input) still gives CI a JUnit report: one test case in
// error, carrying the message.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "hotmesh/core/vec3.hpp"
#include "hotmesh/api/wall_deviation_report.hpp"

namespace hotmesh::api {

/// Distances of some nodes to a reference shape.
struct DistanceCheck {
  std::string reference;        ///< what the nodes were measured against
  std::size_t nodes = 0;
  double max_distance = 0.0;
  double mean_distance = 0.0;
  std::int64_t worst_node = 0;  ///< node id in the mesh file
  geometry::Vec3 worst_point;
  /// The two-sided distance between the faces and the reference shape (or why it was not
  /// measured: a wall without a surface).
  WallCheck wall;
  bool passed = true;           ///< max_distance <= tolerance, and the wall's within the wall tolerance
};

struct PatchCheck : DistanceCheck {
  std::string patch;
  double seconds = 0.0;
  /// Per part of a reference made of separate parts (faces forming several profiles), the
  /// nodes nearest to that part; empty for a reference of one piece.
  std::vector<DistanceCheck> parts;
};

struct CheckResult {
  std::string mesh;
  std::string cad;        ///< empty without CAD
  std::string case_file;  ///< empty without --case
  double tolerance = 0.0;
  /// The largest two-sided distance allowed for the faces (--wall-tol); none: reported only.
  std::optional<double> wall_tolerance;
  std::string unit;
  std::vector<PatchCheck> patches;
  /// The checked mesh's cell quality (mesh_quality_json): the scaled Jacobian and the measures
  /// a flow solver uses; reported, not judged.
  nlohmann::json quality;

  bool passed() const;
};

std::string check_text(const CheckResult& result);
std::string check_json(const CheckResult& result);
std::string check_junit(const CheckResult& result);
/// The JUnit report of a check that could not be made: one test case named "input" in error,
/// of `type` ("input error", "internal error", ...), carrying `message`. `subject` is the mesh
/// (or the case file) the check was about.
std::string check_junit_error(const std::string& subject, const std::string& type, const std::string& message);

}  // namespace hotmesh::api
