// hotmesh sample tests: a sample's files in a temporary folder, where its script runs its
// cases as a user runs them (each case <run>.yaml deformed into <run>-out/ beside it), the
// outputs of those runs, and what the script printed.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/mesh/mesh.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::samples {

struct SampleFolder {
  test::TempDir dir;
  std::filesystem::path folder;  ///< dir/<sample>

  explicit SampleFolder(std::string_view sample) : folder(dir / sample) {}

  /// Runs the folder's shell script with the hotmesh built here (HOTMESH): exit code, output.
  test::CommandResult run_script(const std::string& script) const {
    return test::run_command("HOTMESH=" + test::shell_quote(HOTMESH_EXE) + " sh " +
                             test::shell_quote((folder / script).string()) + " 2>&1");
  }
  /// The report.json and deformed.msh of case <run>.yaml's run.
  nlohmann::json report(const std::string& run) const {
    return nlohmann::json::parse(test::read_text(folder / (run + "-out") / "report.json"));
  }
  mesh::Mesh deformed(const std::string& run) const { return io::read_gmsh(folder / (run + "-out") / "deformed.msh"); }
};

/// How many times `what` occurs in `text`.
inline std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace hotmesh::samples
