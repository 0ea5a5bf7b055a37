// hotmesh tests (io): the case-file fixture shared by test_case_file.cpp and
// test_case_patches.cpp: a folder with a mesh, CAD and table files, a case written into it and
// read back, the problems it gives.
#pragma once

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/case_file.hpp"
#include "test_support.hpp"

namespace hotmesh::io::test_case {

namespace fs = std::filesystem;

/// The smallest valid case; tests append keys from line 4 on.
constexpr std::string_view kBase =
    "mesh: mesh.msh\n"
    "patches:\n"
    "  wall: {role: fixed}\n";

/// The same with the axis set, for tables and periodic pairs; appended patches start on line 5.
constexpr std::string_view kBaseWithAxis =
    "mesh: mesh.msh\n"
    "axis: {origin: [0, 0, 0], direction: [0, 0, 1]}\n"
    "patches:\n"
    "  wall: {role: fixed}\n";

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

class CaseFile : public ::testing::Test {
 protected:
  void SetUp() override {
    test::write_text(dir / "mesh.msh", "$MeshFormat\n");
    test::write_text(dir / "part.step", "ISO-10303-21;\n");
    test::write_text(dir / "part.stl", "solid\n");
    test::write_text(dir / "ramp.csv", "r,z,dr,dz\n1,0,0,0.1\n1,1,0,0.2\n");
    test::write_text(dir / "blade.csv",
                     "id,x,y,z,dx,dy,dz\n1,0,0,0,0,0,0.1\n2,1,0,0,0,0,0.1\n3,2,0,0,0,0,0.1\n4,3,0,0,0,0,0.1\n");
    test::write_text(dir / "plane.csv", "x,y,dx,dy\n0,0,0,0.1\n1,0,0,0.1\n");
    test::write_text(dir / "bad.csv", "x,y,dq,dy\n0,0,0,0\n");
  }

  fs::path case_path() const { return dir / "case.yaml"; }
  /// "<case file>:<line>: ", the start of every problem on that line.
  std::string at(int line) const { return case_path().string() + ":" + std::to_string(line) + ": "; }

  Case parse(std::string_view yaml) {
    test::write_text(case_path(), yaml);
    return read_case(case_path());
  }
  std::string error_of(std::string_view yaml) {
    try {
      parse(yaml);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  }
  std::string error_with(std::string_view extra) { return error_of(std::string(kBase) + std::string(extra)); }
  std::string error_with_axis(std::string_view extra) {
    return error_of(std::string(kBaseWithAxis) + std::string(extra));
  }

  test::TempDir dir;
};

class CaseAgainstMesh : public CaseFile {
 protected:
  std::string mesh_error(std::string_view yaml, const mesh::Mesh& mesh) {
    const Case c = parse(yaml);
    try {
      check_case_against_mesh(c, mesh);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  }
};

}  // namespace hotmesh::io::test_case
