// hotmesh tests: the files of CalculiX's test suite (Debian's calculix-ccx-test) that hotmesh
// refused while ccx read or wrote them: results with blocks of more than six components
// (sc123's SDV, written again by the installed ccx), decks with a node of the number only
// (planestress3), an empty field (shell1), more nodes on an element's line than its type has
// (beampsensfreq), a surface on shell or beam faces (contact10, contact11); and the
// displacements of shells and beams, which ccx writes on the 3D elements it expands them
// into, against ccx's own *NODE FILE, OUTPUT=2D of the same model.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <regex>

#include "calculix_runs.hpp"
#include "calculix_suite.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/calculix.hpp"

namespace hotmesh::io {
namespace {

using ::testing::HasSubstr;
using geometry::Vec3;
using test::TempDir;

class CcxSuiteFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!test::have_ccx_suite()) GTEST_SKIP() << "Debian's calculix-ccx-test is not installed; scripts/install-deps.sh installs it";
  }
  InpDeck deck(const std::string& job) { return read_inp(test::ccx_suite_deck(dir.path(), job)); }
  /// `job` solved by the installed ccx in the temporary folder, its deck changed by `edit`.
  void solve(const std::string& job, const std::string& edited_job = "", const std::regex& find = std::regex("$^"),
             const std::string& replace = "") {
    if (!test::have_ccx()) GTEST_SKIP() << "ccx (Debian package calculix-ccx) is not installed";
    const std::string name = edited_job.empty() ? job : edited_job;
    test::write_text(dir / (name + ".inp"), std::regex_replace(*test::ccx_suite_text(job + ".inp"), find, replace));
    const test::CommandResult run = test::run_ccx(dir.path(), name);
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  TempDir dir;
};

// sc123.frd:162 of ccx 2.20: the SDV block's 60 components on a " -1" record and nine " -2"
// records with blank node columns. Every block is read, each SDV node with its 60 values
// (the reader counts them against the block's components), and DISP equals the .dat printout.
TEST_F(CcxSuiteFiles, Sc123ResultsWithSixtyStateVariablesPerNodeAreRead) {
  solve("sc123");
  const FrdResults results = read_frd(dir / "sc123.frd");
  std::vector<std::string> names;
  for (const FrdBlock& b : results.blocks) names.push_back(b.name);
  EXPECT_GE(std::count(names.begin(), names.end(), "SDV"), 1);
  const auto disps = results.displacements();
  ASSERT_FALSE(disps.empty());
  const FrdBlock* sdv = results.companion(*disps.back(), "SDV");
  ASSERT_NE(sdv, nullptr);
  EXPECT_EQ(sdv->nodes, disps.back()->nodes);
  const auto printouts = test::dat_displacements(test::read_text(dir / "sc123.dat"));
  ASSERT_EQ(printouts.size(), disps.size());
  for (std::size_t i = 0; i < disps.back()->nodes.size(); ++i) {
    const Vec3 printed = printouts.back().at(disps.back()->nodes[i]);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(disps.back()->values[i][k], printed[k], 1e-5 * std::max(1e-12, norm(printed)));
  }
}

// planestress3.inp:9, `1` alone: ccx puts the node at the origin.
TEST_F(CcxSuiteFiles, NodeOfTheNumberOnlyIsAtTheOrigin) {
  const InpDeck d = deck("planestress3");
  EXPECT_EQ(d.nodes.at(1), (Vec3{0, 0, 0}));
  EXPECT_EQ(d.nodes.at(2), (Vec3{10, 0, 0}));
  EXPECT_EQ(d.kind(), ModelKind::plane);
}

// shell1.inp:27, `21, 7.5e-01, 1.0, ,0.0`: the empty third coordinate is 0, the fifth field is not read.
TEST_F(CcxSuiteFiles, EmptyCoordinateIsZeroAndFieldsAfterZAreNotRead) {
  const InpDeck d = deck("shell1");
  EXPECT_EQ(d.nodes.at(21), (Vec3{0.75, 1.0, 0.0}));
  EXPECT_EQ(d.kind(), ModelKind::solid);  // S8R shells, expanded into C3D20R
  EXPECT_TRUE(d.elements.at(1).expanded);
}

// beampsensfreq.inp:270: ten nodes on the line of a C3D8; ccx reads the first eight.
TEST_F(CcxSuiteFiles, ElementTakesItsTypesNodeCountFromALineThatHasMore) {
  const InpDeck d = deck("beampsensfreq");
  EXPECT_EQ(d.elements.at(1).nodes, (std::vector<std::int64_t>{1, 10, 95, 19, 61, 105, 222, 192}));
  EXPECT_EQ(d.elements.at(2).nodes, (std::vector<std::int64_t>{10, 2, 13, 95, 105, 34, 134, 222}));
}

// contact10 and contact11: the slave surface is a face of a shell (S8) or of a beam (B32R). It
// is listed as unusable, the deck is read, and naming it says why and where.
TEST_F(CcxSuiteFiles, SurfaceOnShellOrBeamFacesIsListedAsUnusableAndTheRestIsRead) {
  for (const char* job : {"contact10", "contact11"}) {
    const InpDeck d = deck(job);
    const DeckSet& slave = d.surfaces.at("SSLAV");
    EXPECT_THAT(slave.unusable, HasSubstr("a beam or shell")) << job;
    EXPECT_THAT(slave.unusable, HasSubstr("give a *NSET of the wall's nodes instead")) << job;
    EXPECT_TRUE(d.surfaces.at("SMAST").unusable.empty()) << job;
    EXPECT_EQ(d.set_nodes("SMAST").size(), 4u) << job;  // a C3D8 face
    try {
      d.set_nodes("SSLAV");
      ADD_FAILURE() << job << ": the unusable surface gave nodes";
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(":" + std::to_string(slave.place.line) + ": surface SSLAV is of no use to hotmesh"));
    }
  }
}

/// The table of `set` from the default (expanded) results and from ccx's OUTPUT=2D results
/// agree to `relative` of the largest displacement, node by node.
void expect_same_tables(const CalculixTable& expanded, const CalculixTable& own, double relative) {
  ASSERT_EQ(expanded.samples.ids, own.samples.ids);
  double scale = 0.0;
  for (const Vec3& u : own.samples.deflections) scale = std::max(scale, norm(u));
  ASSERT_GT(scale, 0.0);
  for (std::size_t i = 0; i < own.samples.size(); ++i) {
    EXPECT_LE(distance(expanded.samples.deflections[i], own.samples.deflections[i]), relative * scale)
        << "node " << own.samples.ids[i];
  }
}

// Shells (S8R) and beams (B31): ccx 2.20 writes them as C3D20R and C3D8I elements on new nodes
// by default; the deck's nodes get the mean of the nodes made of them, which is what ccx
// itself writes for them with *NODE FILE, OUTPUT=2D (to the six digits of the .frd).
TEST_F(CcxSuiteFiles, ExpandedShellAndBeamDisplacementsEqualCcxsOwnOutputOnTheDecksNodes) {
  for (const char* job : {"shell1", "b31"}) {
    solve(job);
    solve(job, std::string(job) + "_2d", std::regex(R"(\*NODE FILE[^\n]*)", std::regex::icase), "*NODE FILE,OUTPUT=2D");
    const FrdResults expanded = read_frd(dir / (std::string(job) + ".frd"));
    const FrdResults own = read_frd(dir / (std::string(job) + "_2d.frd"));
    const InpDeck d = read_inp(dir / (std::string(job) + ".inp"));
    EXPECT_FALSE(expanded.nodes.contains(1)) << job << ": the default output holds the deck's nodes";
    EXPECT_TRUE(own.nodes.contains(1)) << job;
    const CalculixSelection selection{dir / (std::string(job) + ".frd"), dir / (std::string(job) + ".inp"), "NALL", {}};
    expect_same_tables(calculix_table(expanded, d, selection), calculix_table(own, d, selection), 2e-5);
  }
}

// Results without the expanded elements (the element block cut out): the deck's shell nodes
// have no value, and the message says what to write.
TEST_F(CcxSuiteFiles, ShellNodesWithoutTheirExpansionSayToWriteOutput2D) {
  solve("shell1");
  std::string text = test::read_text(dir / "shell1.frd");
  const std::size_t from = text.find("    3C");
  const std::size_t to = text.find(" -3\n", from) + 4;
  text.erase(from, to - from);
  const FrdResults results = parse_frd(text, "shell1.frd");
  const InpDeck d = read_inp(dir / "shell1.inp");
  try {
    calculix_table(results, d, {dir / "shell1.frd", dir / "shell1.inp", "NALL", {}});
    ADD_FAILURE() << "a table without the expanded elements";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("nor can hotmesh take it from the nodes ccx expands its S8R element"));
    EXPECT_THAT(e.what(), HasSubstr("write *NODE FILE, OUTPUT=2D"));
  }
}

}  // namespace
}  // namespace hotmesh::io
