// Tests of the stator-well sector in engine formats (make_stator_well --engine-formats): the
// structured multi-block CGNS file reads to the .msh sample's mesh (the interfaces merged), and
// `hotmesh deform` on the CGNS and OpenFOAM cases moves the sector to the same mesh as the .msh
// case, node for node; cgnscheck passes deformed.cgns and checkMesh the written-back polyMesh.
// A sector of about 2 000 cells, 1 increment instead of 16, solved to 1e-13 (the results
// agree to the solver's tolerance, the nodes being numbered differently): 30 s in Release.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <tuple>

#include "foam_fixtures.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::samples::stator_well {
namespace {

using geometry::Vec3;
using ::testing::HasSubstr;

/// For each node of `from`, the node of `to` at the same place (within 1e-12 of the size).
std::vector<std::size_t> same_places(const mesh::Mesh& from, const mesh::Mesh& to) {
  std::map<std::tuple<double, double, double>, std::size_t> at;
  for (std::size_t n = 0; n < to.node_count(); ++n) at[{to.points[n].x, to.points[n].y, to.points[n].z}] = n;
  const double tolerance = 1e-12 * mesh::bounding_diagonal(from.points);
  std::vector<std::size_t> map(from.node_count());
  for (std::size_t n = 0; n < from.node_count(); ++n) {
    const Vec3& p = from.points[n];
    auto it = at.lower_bound({p.x - tolerance, -1e300, -1e300});
    bool found = false;
    for (; it != at.end() && std::get<0>(it->first) <= p.x + tolerance && !found; ++it) {
      const Vec3& q = to.points[it->second];
      if (norm(q - p) <= tolerance) {
        map[n] = it->second;
        found = true;
      }
    }
    EXPECT_TRUE(found) << "node " << n + 1 << " at " << p.x << " " << p.y << " " << p.z;
  }
  return map;
}

/// The largest distance between `a`'s nodes and `b`'s nodes `map`s them to, over the size.
double largest_difference(const mesh::Mesh& a, const mesh::Mesh& b, const std::vector<std::size_t>& map) {
  double worst = 0.0;
  for (std::size_t n = 0; n < a.node_count(); ++n) worst = std::max(worst, norm(a.points[n] - b.points[map[n]]));
  return worst / mesh::bounding_diagonal(a.points);
}

std::size_t face_count(const mesh::Mesh& m, const std::string& patch) {
  const mesh::Patch* p = m.find_patch(patch);
  return p ? p->faces.size() : 0;
}

class StatorWellEngineFormats : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir;
    const auto generate = test::run_command(std::string(HOTMESH_MAKE_STATOR_WELL) + " --engine-formats --cells 2000 " +
                                            test::shell_quote(dir_->path().string()));
    ASSERT_EQ(generate.exit_code, 0) << generate.output;
    for (const char* name : {"case_small.yaml", "case_small_cgns.yaml", "case_small_foam.yaml"}) {
      std::string text = test::read_text(*dir_ / name);
      const std::string from = "solver: {increments: 16}";
      ASSERT_NE(text.find(from), std::string::npos);
      text.replace(text.find(from), from.size(), "solver: {increments: 1, newton_tolerance: 1.0e-13, pcg_tolerance: 1.0e-13, max_newton_iterations: 100}");
      test::write_text(*dir_ / name, text);
    }
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::filesystem::path dir() { return dir_->path(); }

  /// hotmesh deform on a case file of the folder; its output folder.
  static std::filesystem::path deform(const std::string& case_file) {
    const auto out = dir() / (case_file + "-out");
    if (std::filesystem::exists(out / "deformed.msh")) return out;
    const auto run = test::run_command(std::string(HOTMESH_EXE) + " -q deform " +
                                       test::shell_quote((dir() / case_file).string()) + " -o " +
                                       test::shell_quote(out.string()));
    EXPECT_EQ(run.exit_code, 0) << run.output;
    return out;
  }

 private:
  static test::TempDir* dir_;
};
test::TempDir* StatorWellEngineFormats::dir_ = nullptr;

TEST_F(StatorWellEngineFormats, MultiBlockCgnsReadsToTheMeshOfTheMshFile) {
  const mesh::Mesh msh = io::read_mesh(dir() / "stator_well.msh").mesh;
  const mesh::Mesh cgns = io::read_mesh(dir() / "stator_well.cgns").mesh;
  EXPECT_EQ(cgns.node_count(), msh.node_count());  // the blocks' shared sides merged
  EXPECT_EQ(cgns.cell_count(), msh.cell_count());
  same_places(msh, cgns);
  for (const mesh::Patch& p : msh.patches) EXPECT_EQ(face_count(cgns, p.name), p.faces.size()) << p.name;
  const auto check = test::run_command(std::string(HOTMESH_CGNSCHECK) + " " +
                                       test::shell_quote((dir() / "stator_well.cgns").string()));
  EXPECT_EQ(check.exit_code, 0) << check.output;
  EXPECT_THAT(check.output, ::testing::Not(HasSubstr("ERROR")));
}

TEST_F(StatorWellEngineFormats, CgnsCaseMovesToTheMeshOfTheMshCase) {
  if (test::under_sanitizers()) GTEST_SKIP() << "half a minute in the Release build; run there";
  const mesh::Mesh reference = io::read_mesh(deform("case_small.yaml") / "deformed.msh").mesh;
  const auto out = deform("case_small_cgns.yaml");
  const mesh::Mesh start = io::read_mesh(dir() / "stator_well.cgns").mesh;
  const mesh::Mesh moved = io::read_mesh(out / "deformed.cgns").mesh;
  const mesh::Mesh msh = io::read_mesh(dir() / "stator_well.msh").mesh;
  ASSERT_EQ(moved.node_count(), start.node_count());
  const auto map = same_places(start, msh);  // CGNS node -> .msh node, before the motion
  EXPECT_LT(largest_difference(moved, reference, map), 1e-12);
  const auto check = test::run_command(std::string(HOTMESH_CGNSCHECK) + " " +
                                       test::shell_quote((out / "deformed.cgns").string()));
  EXPECT_EQ(check.exit_code, 0) << check.output;
  EXPECT_THAT(check.output, ::testing::Not(HasSubstr("ERROR")));
}

TEST_F(StatorWellEngineFormats, FoamCaseMovesToTheMeshOfTheMshCaseAndPassesCheckMesh) {
  const mesh::Mesh msh = io::read_mesh(dir() / "stator_well.msh").mesh;
  const mesh::Mesh foam = io::read_mesh(dir() / "stator_well_foam").mesh;
  EXPECT_EQ(foam.points, msh.points);  // the polyMesh keeps the .msh's node order
  for (const mesh::Patch& p : msh.patches) EXPECT_EQ(face_count(foam, p.name), p.faces.size()) << p.name;
  if (test::under_sanitizers()) GTEST_SKIP() << "half a minute in the Release build; run there";
  const mesh::Mesh reference = io::read_mesh(deform("case_small.yaml") / "deformed.msh").mesh;
  const auto out = deform("case_small_foam.yaml");
  const mesh::Mesh moved = io::read_mesh(out / "polyMesh").mesh;
  std::vector<std::size_t> identity(moved.node_count());
  for (std::size_t n = 0; n < identity.size(); ++n) identity[n] = n;
  EXPECT_LT(largest_difference(moved, reference, identity), 1e-12);
  if (test::foam::block_mesh_command().empty()) GTEST_SKIP() << "OpenFOAM is not installed: scripts/install-deps.sh";
  const auto r = test::foam::check_mesh(dir() / "stator_well_foam", out / "polyMesh", dir() / "check");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("Mesh OK."));
}

}  // namespace
}  // namespace hotmesh::samples::stator_well
