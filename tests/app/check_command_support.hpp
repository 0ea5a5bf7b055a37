// hotmesh tests: what the tests of `hotmesh check` share (test_check_command.cpp,
// test_check_case_files.cpp): running the command, its JSON and JUnit reports, nodes to move.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "hotmesh/mesh/mesh.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::app::check_test {

using test::run_command;
using test::shell_quote;
using Json = nlohmann::json;

inline test::CommandResult hotmesh(const std::string& arguments) {
  return run_command(std::string(HOTMESH_EXE) + " " + arguments);
}

inline std::string q(const std::filesystem::path& path) { return shell_quote(path.string()); }

/// The node in the middle of a patch's node list (sorted by index).
inline mesh::NodeId middle_node(const mesh::Mesh& mesh, const std::string& patch) {
  const auto& nodes = mesh.find_patch(patch)->nodes;
  return nodes[nodes.size() / 2];
}

/// The node of `patch` nearest to `point`.
inline mesh::NodeId nearest_node(const mesh::Mesh& mesh, const std::string& patch, const geometry::Vec3& point) {
  const auto& nodes = mesh.find_patch(patch)->nodes;
  return *std::min_element(nodes.begin(), nodes.end(), [&](mesh::NodeId a, mesh::NodeId b) {
    return distance(mesh.points[static_cast<std::size_t>(a)], point) < distance(mesh.points[static_cast<std::size_t>(b)], point);
  });
}

inline const std::filesystem::path kSamples = std::filesystem::path(HOTMESH_SOURCE_DIR) / "samples";

/// A report file parsed by a real XML parser, as CI systems do: "<tests> <failures> <errors>",
/// then per test case its name and "pass", "failure" or "error", then every message.
inline test::CommandResult parse_junit(const std::filesystem::path& report) {
  return run_command(
      "python3 -c \"import sys, xml.etree.ElementTree as E; s = E.parse(sys.argv[1]).getroot(); "
      "print(s.get('tests'), s.get('failures'), s.get('errors'), "
      "[(c.get('name'), 'failure' if c.find('failure') is not None else 'error' if c.find('error') is not None "
      "else 'pass') for c in s.iter('testcase')], "
      "[m.get('message') for m in list(s.iter('failure')) + list(s.iter('error'))])\" " +
      q(report));
}

/// The JSON report of a check, with its exit code.
inline std::pair<int, Json> check_json(const std::string& arguments) {
  const auto r = hotmesh("-q check --format json " + arguments);
  const auto start = r.output.find('{');
  if (start == std::string::npos) return {r.exit_code, Json{{"output", r.output}}};
  return {r.exit_code, Json::parse(r.output.substr(start))};
}

}  // namespace hotmesh::app::check_test
