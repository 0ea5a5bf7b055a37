// Tests of the case file's `quality:` limits (issue 48 item 2) on the paper's ramp (the ramp2d
// sample): without limits its final mesh has a face of 69.8 degrees and a cell of scaled
// Jacobian 0.307. A limit the motion cannot keep ends the run with exit code 1 after the
// increment's halvings, naming the limit and the worst cell, with the last valid mesh kept
// and within the limits; limits the motion keeps change nothing; wrong limits are user errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "deform_cases.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "test_support.hpp"

namespace hotmesh::app {
namespace {

using test::hotmesh;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

/// The ramp sample's case with `quality` (a YAML map, or empty for none).
std::string ramp_case(const std::string& quality) {
  return "mesh: ramp2d.msh\nsolver: {increments: 16}\n" + (quality.empty() ? "" : "quality: " + quality + "\n") +
         "patches:\n  left: {role: fixed}\n  right: {role: slip}\n  top: {role: fixed}\n"
         "  bottom: {role: prescribed, deflection: {file: ramp.csv, degree: 1}}\n";
}

struct DeformRun {
  test::CommandResult command;
  nlohmann::json report;
  fs::path out;
};

DeformRun deform(const test::RampCase& c) {
  DeformRun r;
  r.out = c.dir / "out";
  r.command = hotmesh("deform " + c.case_file() + " -o " + test::shell_quote(r.out.string()) + " --threads 1");
  if (fs::exists(r.out / "report.json")) r.report = nlohmann::json::parse(test::read_text(r.out / "report.json"));
  return r;
}

TEST(DeformQualityLimits, ALimitTheMotionCannotKeepEndsTheRunWithTheLastValidMeshWithinIt) {
  test::RampCase unlimited_case(ramp_case(""));
  const DeformRun unlimited = deform(unlimited_case);
  ASSERT_EQ(unlimited.command.exit_code, 0) << unlimited.command.output;
  const double unconstrained = unlimited.report["quality"]["non_orthogonality"]["max"].get<double>();
  ASSERT_GT(unconstrained, 60.0);

  test::RampCase limited(ramp_case("{max_non_orthogonality: 50}"));
  const DeformRun r = deform(limited);
  EXPECT_EQ(r.command.exit_code, 1) << r.command.output;
  EXPECT_THAT(r.command.output, HasSubstr("above quality.max_non_orthogonality 50 deg, the worst cell"));
  EXPECT_THAT(r.command.output, HasSubstr("cells beyond the case's quality limits; no cell inverted"));
  EXPECT_EQ(r.report["status"], "failed");
  EXPECT_EQ(r.report["failure"]["kind"], "quality_limits");
  // Halved as far as the solver may before giving up, and the last valid mesh keeps the limit.
  EXPECT_LT(r.report["stage_reached"].get<double>(), 1.0);
  EXPECT_GT(r.report["stage_reached"].get<double>(), 0.0);
  EXPECT_LE(r.report["quality"]["non_orthogonality"]["max"].get<double>(), 50.0);
  EXPECT_TRUE(fs::exists(r.out / "deformed.msh"));
  EXPECT_TRUE(fs::exists(r.out / "failed.vtu"));
}

TEST(DeformQualityLimits, LimitsTheMotionKeepsChangeNothing) {
  test::RampCase unlimited_case(ramp_case(""));
  const DeformRun unlimited = deform(unlimited_case);
  ASSERT_EQ(unlimited.command.exit_code, 0) << unlimited.command.output;
  const double angle = unlimited.report["quality"]["non_orthogonality"]["max"].get<double>();
  const double jacobian = unlimited.report["quality"]["min_scaled_jacobian"].get<double>();
  test::RampCase kept(ramp_case(fmt::format("{{max_non_orthogonality: {}, min_scaled_jacobian: {}, max_skewness: 10}}",
                                            angle + 0.05, jacobian - 0.01)));
  const DeformRun r = deform(kept);
  ASSERT_EQ(r.command.exit_code, 0) << r.command.output;
  EXPECT_EQ(io::read_gmsh(r.out / "deformed.msh").points, io::read_gmsh(unlimited.out / "deformed.msh").points);
}

TEST(DeformQualityLimits, AScaledJacobianBelowTheLimitIsRetriedLikeAnInvertedCell) {
  test::RampCase limited(ramp_case("{min_scaled_jacobian: 0.35}"));
  const DeformRun r = deform(limited);
  EXPECT_EQ(r.command.exit_code, 1) << r.command.output;
  EXPECT_THAT(r.command.output, HasSubstr("below quality.min_scaled_jacobian 0.35, the worst cell"));
  EXPECT_GE(r.report["quality"]["min_scaled_jacobian"].get<double>(), 0.35);
  // Its increments were halved before the run gave up.
  std::size_t halved = 0;
  for (const auto& increment : r.report["increments"]) {
    if (increment["stage"][1].get<double>() - increment["stage"][0].get<double>() < 1.0 / 16 - 1e-12) ++halved;
  }
  EXPECT_GE(halved, 4u);
}

TEST(DeformQualityLimits, WrongLimitsAreUserErrorsNamingTheKey) {
  for (const auto& [quality, expected] :
       {std::pair{"{max_non_orthogonality: 95}", "max_non_orthogonality"}, {"{min_scaled_jacobian: 1.5}", "min_scaled_jacobian"},
        {"{max_skewness: -1}", "max_skewness"}, {"{max_orthogonality: 70}", "max_orthogonality"}, {"70", "quality"}}) {
    test::RampCase c(ramp_case(quality));
    const DeformRun r = deform(c);
    EXPECT_EQ(r.command.exit_code, 2) << quality << "\n" << r.command.output;
    EXPECT_THAT(r.command.output, HasSubstr(expected)) << quality;
  }
}

}  // namespace
}  // namespace hotmesh::app
