// Tests of `hotmesh fem` on results of the real ccx (the ring of tests/support/
// calculix_runs.hpp): it lists the output steps and the deck's sets with their node counts,
// writes the table of one set as CSV that reads back to the same numbers, and refuses a set,
// a step or a file it cannot read, and an output that would replace one of its inputs, with
// exit code 2 and a message naming the file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "calculix_runs.hpp"
#include "calculix_suite.hpp"
#include "deform_cases.hpp"
#include "hotmesh/io/calculix.hpp"
#include "hotmesh/io/deflection_csv.hpp"

namespace hotmesh::app {
namespace {

using ::testing::HasSubstr;
using test::shell_quote;

class FemCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!test::have_ccx()) GTEST_SKIP() << "ccx (Debian package calculix-ccx) is not installed; scripts/install-deps.sh installs it";
    test::RingDeck().write(dir.path(), "*NODE FILE");
    const test::CommandResult solved = test::run_ccx(dir.path(), "ring");
    ASSERT_EQ(solved.exit_code, 0) << solved.output;
  }
  test::CommandResult fem(const std::string& arguments) const {
    return test::hotmesh("fem " + shell_quote((dir / "ring.frd").string()) + " --inp " +
                         shell_quote((dir / "ring.inp").string()) + " " + arguments);
  }
  test::TempDir dir;
};

TEST_F(FemCommand, ListsStepsSetsAndSurfaces) {
  const test::CommandResult r = fem("");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("ASCII .frd, 27 nodes"));
  EXPECT_THAT(r.output, HasSubstr("step   1  increment   1  time 1"));
  EXPECT_THAT(r.output, HasSubstr("temperature 400 to 400"));
  EXPECT_THAT(r.output, HasSubstr("step   2  increment   1  time 2"));
  EXPECT_THAT(r.output, HasSubstr("axisymmetric model, 27 nodes, 16 elements, 3 file(s)"));
  EXPECT_THAT(r.output, HasSubstr("largest |u| at step 2 (time 2)"));
  EXPECT_THAT(r.output, ::testing::ContainsRegex("nset +BORE +3 nodes"));
  EXPECT_THAT(r.output, ::testing::ContainsRegex("surface +TOP +9 nodes"));
}

TEST_F(FemCommand, WritesTheTableOfASetThatReadsBackTheSame) {
  const test::CommandResult r = fem("--set outer --step 1 -o " + shell_quote((dir / "outer.csv").string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("meridional (r, z) table of set outer (3 nodes), step 1 (time 1)"));
  const geometry::DeflectionSamples written = io::read_deflection_csv(dir / "outer.csv");
  io::FrdStepChoice step1;
  step1.step = 1;
  const geometry::DeflectionSamples read = io::read_calculix_table({dir / "ring.frd", dir / "ring.inp", "OUTER", step1}).samples;
  EXPECT_EQ(written.frame, geometry::SampleFrame::meridional);
  EXPECT_EQ(written.ids, read.ids);
  EXPECT_EQ(written.points, read.points);
  EXPECT_EQ(written.deflections, read.deflections);
}

TEST_F(FemCommand, RefusesUnknownSetStepAndTruncatedFile) {
  const test::CommandResult set = fem("--set RIM");
  EXPECT_EQ(set.exit_code, 2) << set.output;
  EXPECT_THAT(set.output, HasSubstr((dir / "ring.inp").string() + ": no node set or surface 'RIM'; its node sets: BORE"));

  const test::CommandResult step = fem("--set BORE --step 9");
  EXPECT_EQ(step.exit_code, 2) << step.output;
  EXPECT_THAT(step.output, HasSubstr((dir / "ring.frd").string() + ": no displacements at step 9"));

  const std::string frd = test::read_text(dir / "ring.frd");
  test::write_text(dir / "ring.frd", frd.substr(0, frd.size() - 200));
  const test::CommandResult cut = fem("");
  EXPECT_EQ(cut.exit_code, 2) << cut.output;
  EXPECT_THAT(cut.output, ::testing::ContainsRegex("ring\\.frd:[0-9]+: .*truncated"));
}

// -o naming the .frd replaced the results with the table and exited 0; so did -o naming the
// deck or a file it includes.
TEST_F(FemCommand, RefusesAnOutputThatIsOneOfItsInputs) {
  for (const char* input : {"ring.frd", "ring.inp", "ring_sets.inp"}) {
    const std::string before = test::read_text(dir / input);
    const test::CommandResult r = fem("--set outer -o " + shell_quote((dir / input).string()));
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_THAT(r.output, HasSubstr((dir / input).string() + ": this output would replace an input file"));
    EXPECT_EQ(test::read_text(dir / input), before) << input;
  }
}

// A deck that redefines an element after a *SURFACE used one of its faces: a segmentation
// fault while the surfaces were listed.
TEST(FemCommandDecks, DeckRedefiningAnElementASurfaceUsedIsRefusedWithExitCode2) {
  const auto deck = test::data_path("calculix/element-redefined-as-beam.inp");
  const test::CommandResult r = test::hotmesh("fem " + shell_quote(test::data_path("calculix/plate.frd").string()) +
                                              " --inp " + shell_quote(deck.string()));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr(deck.string() + ":14: element 1 is defined already"));
}

// NaN displacements were listed as "largest |u| nan" (or hidden behind the other nodes').
TEST(FemCommandDecks, ResultsWithNanDisplacementsAreRefusedWithExitCode2) {
  const auto frd = test::data_path("calculix/plate-nan-displacement.frd");
  const test::CommandResult r = test::hotmesh("fem " + shell_quote(frd.string()) + " --inp " +
                                              shell_quote(test::data_path("calculix/plate.inp").string()));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr(frd.string() + ":31: node 3 has the value nan in the DISP block"));
}

/// An ASCII .frd of `n` nodes on a line, x = 1 + i/1000, each displaced by 1e-6 along x.
std::string line_of_nodes_frd(int n) {
  std::string frd = fmt::format("    1C\n    2C{:18}{:12}{:37}1\n", "", n, "");
  for (int i = 1; i <= n; ++i) frd += fmt::format(" -1{:10}{:12.5E}{:12.5E}{:12.5E}\n", i, 1 + i * 1e-3, 0.0, 0.0);
  frd += fmt::format(" -3\n  100CL  101 1.000000000{:12}                     0    1           1\n", n);
  frd += " -4  DISP        4    1\n -5  D1          1    2    1    0\n -5  D2          1    2    2    0\n"
         " -5  D3          1    2    3    0\n -5  ALL         1    2    0    0    1ALL\n";
  for (int i = 1; i <= n; ++i) frd += fmt::format(" -1{:10}{:12.5E}{:12.5E}{:12.5E}\n", i, 1e-6, 0.0, 0.0);
  return frd + " -3\n 9999\n";
}

// Each set's largest |u| indexed the whole DISP block again: 10 000 sets of one node with
// results of 50 000 nodes took half a minute, a deck of 10^5 small sets many minutes. The
// index is made once (a fraction of a second here; the bound leaves room for the sanitizers).
TEST(FemCommandDecks, ManySetsAreListedWithOneIndexOfTheResults) {
  test::TempDir dir;
  constexpr int kNodes = 50'000;
  constexpr int kSets = 10'000;
  std::string deck = "*NODE\n";
  for (int i = 1; i <= kNodes; ++i) deck += fmt::format("{}, {}, 0\n", i, 1 + i * 1e-3);
  deck += "*ELEMENT, TYPE=CAX4\n1, 1, 2, 3, 4\n";
  for (int k = 1; k <= kSets; ++k) deck += fmt::format("*NSET, NSET=S{}\n{}\n", k, k);
  test::write_text(dir / "many.inp", deck);
  test::write_text(dir / "many.frd", line_of_nodes_frd(kNodes));
  const test::CommandResult r = test::run_command("timeout 20 " + std::string(HOTMESH_EXE) + " fem " +
                                                  shell_quote((dir / "many.frd").string()) + " --inp " +
                                                  shell_quote((dir / "many.inp").string()));
  ASSERT_EQ(r.exit_code, 0) << r.output.substr(0, 2000);
  EXPECT_THAT(r.output, ::testing::ContainsRegex("nset +S9999 +1 nodes  largest \\|u\\| 1e-06 at node 9999"));
}

// contact10 of CalculiX's test suite: a C3D8 block and an S8 shell whose face S2 is the slave
// surface. The deck is listed, the shell's surface as unusable with the reason; naming it
// exits 2 with its line; the block's surface gives its table.
TEST(FemCommandOnCcxSuite, ListsASurfaceOfShellFacesAsUnusableAndReadsTheRest) {
  if (!test::have_ccx_suite()) GTEST_SKIP() << "Debian's calculix-ccx-test is not installed; scripts/install-deps.sh installs it";
  test::TempDir dir;
  const std::filesystem::path inp = test::ccx_suite_deck(dir.path(), "contact10");
  test::write_text(dir / "contact10.frd", test::ccx_suite_results_text("contact10"));
  const std::string files = shell_quote((dir / "contact10.frd").string()) + " --inp " + shell_quote(inp.string());
  const test::CommandResult list = test::hotmesh("fem " + files);
  ASSERT_EQ(list.exit_code, 0) << list.output;
  EXPECT_THAT(list.output, HasSubstr("solid model, 16 nodes, 2 elements"));
  EXPECT_THAT(list.output, ::testing::ContainsRegex("surface +SSLAV +unusable: the face S2 of element 2 \\(S8, a beam or shell\\)"));
  EXPECT_THAT(list.output, ::testing::ContainsRegex("surface +SMAST +4 nodes"));
  const test::CommandResult slave = test::hotmesh("fem " + files + " --set SSLAV");
  EXPECT_EQ(slave.exit_code, 2) << slave.output;
  EXPECT_THAT(slave.output, HasSubstr(inp.string() + ":45: surface SSLAV is of no use to hotmesh"));
  const test::CommandResult master = test::hotmesh("fem " + files + " --set SMAST");
  EXPECT_EQ(master.exit_code, 0) << master.output;
  EXPECT_THAT(master.output, HasSubstr("id,x,y,z,dx,dy,dz"));
}

}  // namespace
}  // namespace hotmesh::app
