// Tests of the case file's `deflection: {calculix: {frd, inp, set, step | time}}` (io/src/
// case_file.cpp) on results of the real ccx: the table it gives is the set's, its files are
// inputs of the run, and each problem (a set or step the results do not have, a truncated
// .frd, keys missing or given with `file:`) is reported at its line of the case file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "calculix_runs.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/case_file.hpp"

namespace hotmesh::io {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class CalculixCase : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!test::have_ccx()) GTEST_SKIP() << "ccx (Debian package calculix-ccx) is not installed; scripts/install-deps.sh installs it";
    test::RingDeck().write(dir.path(), "*NODE FILE");
    const test::CommandResult solved = test::run_ccx(dir.path(), "ring");
    ASSERT_EQ(solved.exit_code, 0) << solved.output;
    test::write_text(dir / "mesh.msh", "$MeshFormat\n");
  }

  /// A case whose patch `rim` (line 5) takes `deflection` (from line 6 on, indented by 6).
  Case parse(const std::string& deflection) const {
    return parse_case("mesh: mesh.msh\naxis: {origin: [0, 0, 0], direction: [0, 0, 1]}\npatches:\n"
                      "  rim:\n    role: prescribed\n    deflection:\n" + deflection,
                      dir / "case.yaml");
  }
  std::string error_with(const std::string& deflection) const {
    try {
      parse(deflection);
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no error)";
  }
  std::string at(int line) const { return (dir / "case.yaml").string() + ":" + std::to_string(line) + ": "; }

  test::TempDir dir;
};

TEST_F(CalculixCase, GivesTheSetsMeridionalTableAndItsFilesAsInputs) {
  const Case c = parse("      calculix: {frd: ring.frd, inp: ring.inp, set: outer, step: 1}\n      degree: 2\n");
  const DeflectionSpec& d = *c.patches.front().deflection;
  EXPECT_EQ(d.samples.frame, geometry::SampleFrame::meridional);
  EXPECT_EQ(d.samples.size(), 3u);
  EXPECT_EQ(d.degree, 2);
  ASSERT_TRUE(d.calculix.has_value());
  EXPECT_EQ(d.calculix->step, 1);
  EXPECT_EQ(d.calculix->max_temperature, 400.0);
  EXPECT_EQ(d.file, dir / "ring.frd");
  const std::vector<fs::path> inputs = c.inputs();
  for (const char* name : {"ring.frd", "ring.inp", "ring_nodes.inp", "ring_sets.inp"}) {
    EXPECT_NE(std::find(inputs.begin(), inputs.end(), dir / name), inputs.end()) << name;
  }
}

TEST_F(CalculixCase, StepLastAndTimeChooseTheBlock) {
  EXPECT_EQ(parse("      calculix: {frd: ring.frd, inp: ring.inp, set: BORE, step: last}\n")
                .patches.front().deflection->calculix->step, 2);
  EXPECT_EQ(parse("      calculix: {frd: ring.frd, inp: ring.inp, set: BORE, time: 1.0}\n")
                .patches.front().deflection->calculix->step, 1);
}

TEST_F(CalculixCase, ProblemsAreReportedAtTheirKeys) {
  EXPECT_THAT(error_with("      calculix:\n        frd: ring.frd\n        inp: ring.inp\n        set: BORE\n"
                         "        step: 7\n"),
              HasSubstr(at(11) + "patches.rim.deflection.calculix.step: " + (dir / "ring.frd").string() +
                        ": no displacements at step 7; its DISP blocks are at step 1 increment 1 (time 1), "
                        "step 2 increment 1 (time 2)"));
  EXPECT_THAT(error_with("      calculix: {frd: ring.frd, inp: ring.inp}\n"),
              HasSubstr(at(7) + "patches.rim.deflection.calculix.set: missing; give a node set (*NSET) or surface"));
  EXPECT_THAT(error_with("      file: ring.csv\n      calculix: {frd: ring.frd, inp: ring.inp, set: BORE}\n"),
              HasSubstr(at(8) + "patches.rim.deflection.calculix: give either `file:` (a CSV table) or `calculix:`"));
  EXPECT_THAT(error_with("      calculix: {frd: ring.frd, inp: ring.inp, set: BORE, step: first}\n"),
              HasSubstr(at(7) + "patches.rim.deflection.calculix.step: expected `last` or the number of an analysis step "
                        "(*STEP, from 1), got 'first'"));

  const std::string frd = test::read_text(dir / "ring.frd");
  test::write_text(dir / "cut.frd", frd.substr(0, frd.size() / 2));
  EXPECT_THAT(error_with("      calculix: {frd: cut.frd, inp: ring.inp, set: BORE}\n"),
              HasSubstr(at(7) + "patches.rim.deflection.calculix.frd: " + (dir / "cut.frd").string() + ":"));
  EXPECT_THAT(error_with("      calculix: {frd: cut.frd, inp: ring.inp, set: BORE}\n"), HasSubstr("truncated"));
}

// A deck that redefines an element after a *SURFACE used one of its faces: a segmentation
// fault while `hotmesh deform` read the case.
TEST_F(CalculixCase, DeckRedefiningAnElementASurfaceUsedIsReportedAtInp) {
  const auto deck = test::data_path("calculix/element-redefined-as-cax3.inp");
  EXPECT_THAT(error_with(fmt::format("      calculix: {{frd: ring.frd, inp: {}, set: RIM}}\n", deck.string())),
              HasSubstr(at(7) + "patches.rim.deflection.calculix.inp: " + deck.string() +
                        ":11: element 1 is defined already"));
}

}  // namespace
}  // namespace hotmesh::io
