// Tests of `hotmesh deform` driven by CalculiX results (`deflection: {calculix: ...}`): a ring
// of CAX4 elements solved by the real ccx (tests/support/calculix_runs.hpp) moves a sector
// of the same ring, its walls prescribed and sliding over the curves through the deflected
// FEM nodes; a set the deck does not have is refused with exit code 2 at the case's line; a
// plane-stress strip (CPS4) moves the floor of a 2D channel.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "calculix_runs.hpp"
#include "deform_cases.hpp"
#include "hotmesh/io/calculix.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::app {
namespace {

using ::testing::HasSubstr;
using test::shell_quote;

struct Point2 {
  double r, z;
};

double segment_distance(Point2 p, Point2 a, Point2 b) {
  const double dr = b.r - a.r, dz = b.z - a.z;
  const double t = std::clamp(((p.r - a.r) * dr + (p.z - a.z) * dz) / (dr * dr + dz * dz), 0.0, 1.0);
  return std::hypot(p.r - a.r - t * dr, p.z - a.z - t * dz);
}

/// Distance from p to the polyline through the deflected nodes of a table (in its node order).
double distance_to_deflected(Point2 p, const geometry::DeflectionSamples& s) {
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j + 1 < s.size(); ++j) {
    const auto at = [&](std::size_t k) {
      return Point2{s.points[k].x + s.deflections[k].x, s.points[k].y + s.deflections[k].y};
    };
    d = std::min(d, segment_distance(p, at(j), at(j + 1)));
  }
  return d;
}

class RingSector : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!test::have_ccx()) GTEST_SKIP() << "ccx (Debian package calculix-ccx) is not installed; scripts/install-deps.sh installs it";
    test::RingDeck().write(dir.path(), "*NODE OUTPUT");
    const test::CommandResult solved = test::run_ccx(dir.path(), "ring");
    ASSERT_EQ(solved.exit_code, 0) << solved.output;
    io::write_gmsh(dir / "sector.msh", test::annular_sector(4, 2, 3, 0.1, 0.2, 0.0, 0.05, 10.0));
  }

  static std::string wall(const std::string& role, const std::string& set) {
    return fmt::format("{{role: {}, deflection: {{calculix: {{frd: ring.frd, inp: ring.inp, set: {}}}}}}}", role, set);
  }

  test::CommandResult deform(const std::string& patches) {
    test::write_text(dir / "case.yaml", "mesh: sector.msh\naxis: {origin: [0, 0, 0], direction: [0, 0, 1]}\n"
                                        "solver: {increments: 2}\npatches:\n" + patches +
                                            "  per_lo: {role: periodic, partner: per_hi, angle_deg: 10}\n"
                                            "  per_hi: {role: periodic}\n");
    return test::hotmesh("deform " + shell_quote((dir / "case.yaml").string()) + " -o " +
                         shell_quote((dir / "out").string()));
  }

  geometry::DeflectionSamples table(const std::string& set) const {
    return io::read_calculix_table({dir / "ring.frd", dir / "ring.inp", set, {}}).samples;
  }

  test::TempDir dir;
};

TEST_F(RingSector, CcxResultsMoveTheWallsOntoTheDeflectedRing) {
  const test::CommandResult r = deform("  inner: " + wall("prescribed", "BORE") + "\n  outer: " +
                                       wall("prescribed", "outer") + "\n  top: " + wall("sliding", "TOP") +
                                       "\n  bottom: " + wall("sliding", "BOTTOM") + "\n");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const mesh::Mesh moved = io::read_gmsh(dir / "out" / "deformed.msh");
  EXPECT_EQ(mesh::summarize_quality(mesh::scaled_jacobians(moved.cells, moved.points)).inverted_cells, 0u);
  for (const auto& [patch, set] : {std::pair{"inner", "BORE"}, std::pair{"outer", "OUTER"}, std::pair{"top", "TOP"},
                                   std::pair{"bottom", "BOTTOM"}}) {
    const geometry::DeflectionSamples samples = table(set);
    for (const mesh::NodeId n : moved.find_patch(patch)->nodes) {
      const auto& x = moved.points[static_cast<std::size_t>(n)];
      EXPECT_LT(distance_to_deflected({std::hypot(x.x, x.y), x.z}, samples), 1e-9) << patch << " node " << n;
    }
  }
  // report.json says where each table came from, and the set's temperatures at that step.
  const nlohmann::json report = test::read_json(dir / "out" / "report.json");
  std::size_t from_ccx = 0;
  for (const auto& d : report["deflections"]) {
    if (!d.contains("calculix")) continue;
    ++from_ccx;
    EXPECT_EQ(d["calculix"]["step"], 2);
    EXPECT_EQ(d["calculix"]["model"], "axisymmetric");
    EXPECT_EQ(d["calculix"]["max_temperature"], 200.0);
    EXPECT_THAT(d["calculix"]["frd"].get<std::string>(), HasSubstr("ring.frd"));
  }
  EXPECT_EQ(from_ccx, 4u);
  // Heated from 20 to 200 and still spinning (ccx keeps step 1's *DLOAD in step 2): the rim
  // grew by more than the 0.43 mm of the heat alone, by what ccx found for the rim's nodes.
  const geometry::DeflectionSamples rim = table("OUTER");
  const auto [lo, hi] = std::minmax_element(rim.deflections.begin(), rim.deflections.end(),
                                            [](const auto& a, const auto& b) { return a.x < b.x; });
  EXPECT_GT(lo->x, 0.2 * 1.2e-5 * 180);
  for (const mesh::NodeId n : moved.find_patch("outer")->nodes) {
    const auto& x = moved.points[static_cast<std::size_t>(n)];
    EXPECT_GE(std::hypot(x.x, x.y) - 0.2, lo->x - 1e-12) << "outer node " << n;
    EXPECT_LE(std::hypot(x.x, x.y) - 0.2, hi->x + 1e-12) << "outer node " << n;
  }
}

TEST_F(RingSector, SetNotInTheDeckIsRefusedAtItsLine) {
  const test::CommandResult r = deform("  inner: " + wall("prescribed", "BORE") + "\n  outer: " +
                                       wall("prescribed", "RIM") + "\n  top: {role: sliding}\n  bottom: {role: slip}\n");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr(fmt::format("{}:6: patches.outer.deflection.calculix.set: {}: no node set or surface "
                                              "'RIM'; its node sets: BORE (3 nodes), NALL (27 nodes), OUTER (3 nodes)",
                                              (dir / "case.yaml").string(), (dir / "ring.inp").string())));
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "deformed.msh"));
}

/// A plane-stress strip of CPS4 elements under the floor of the coarse ramp channel (x in
/// [0, 2], y in [-0.05, 0]), clamped at x = 0, its upper face 300 degrees hotter than its
/// lower one: it grows along x, and its upper face rises. Surface FLOOR: the faces on y = 0.
std::string strip_deck() {
  constexpr int kColumns = 10;
  std::string deck = "*NODE, NSET=NALL\n";
  for (int j = 0; j <= 1; ++j) {
    for (int i = 0; i <= kColumns; ++i) deck += fmt::format("{}, {}, {}\n", 1 + i + 11 * j, 0.2 * i, -0.05 + 0.05 * j);
  }
  deck += "*ELEMENT, TYPE=CPS4, ELSET=EALL\n";
  for (int i = 0; i < kColumns; ++i) deck += fmt::format("{}, {}, {}, {}, {}\n", 1 + i, 1 + i, 2 + i, 13 + i, 12 + i);
  deck += "*SURFACE, NAME=FLOOR\nEALL, S3\n*NSET, NSET=CLAMP\n1, 12\n*NSET, NSET=HOT, GENERATE\n12, 22\n"
          "*NSET, NSET=COLD, GENERATE\n1, 11\n"
          "*MATERIAL, NAME=STEEL\n*ELASTIC\n200e9, 0.3\n*EXPANSION\n1.2e-5\n"
          "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n0.01\n*INITIAL CONDITIONS, TYPE=TEMPERATURE\nNALL, 20\n"
          "*STEP\n*STATIC\n*BOUNDARY\nCLAMP, 1, 2\n*TEMPERATURE\nHOT, 320\nCOLD, 20\n*NODE FILE\nU\n*END STEP\n";
  return deck;
}

TEST(PlaneStrip, CcxResultsOfAPlaneDeckMoveA2DWall) {
  if (!test::have_ccx()) GTEST_SKIP() << "ccx (Debian package calculix-ccx) is not installed; scripts/install-deps.sh installs it";
  test::TempDir dir;
  test::write_coarse_ramp(dir.path());
  test::write_text(dir / "strip.inp", strip_deck());
  const test::CommandResult solved = test::run_ccx(dir.path(), "strip");
  ASSERT_EQ(solved.exit_code, 0) << solved.output;
  test::write_text(dir / "case.yaml",
                   "mesh: ramp.msh\nsolver: {increments: 4}\npatches:\n  left: {role: fixed}\n  right: {role: slip}\n"
                   "  top: {role: sliding}\n"
                   "  bottom: {role: prescribed, deflection: {calculix: {frd: strip.frd, inp: strip.inp, set: floor}}}\n");
  const test::CommandResult r = test::hotmesh("deform " + shell_quote((dir / "case.yaml").string()) + " -o " +
                                              shell_quote((dir / "out").string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const geometry::DeflectionSamples floor = io::read_calculix_table({dir / "strip.frd", dir / "strip.inp", "FLOOR", {}}).samples;
  ASSERT_EQ(floor.frame, geometry::SampleFrame::planar);
  // The free end grew along x by alpha * 150 K (the mean heating) * 2 m, and the floor rose as
  // the strip thickened (one row of fully integrated CPS4 elements hardly bends).
  EXPECT_NEAR(floor.deflections.back().x, 1.2e-5 * 150 * 2.0, 0.1e-3);
  EXPECT_GT(floor.deflections.back().y, 1e-5);
  const mesh::Mesh moved = io::read_gmsh(dir / "out" / "deformed.msh");
  for (const mesh::NodeId n : moved.find_patch("bottom")->nodes) {
    const auto& x = moved.points[static_cast<std::size_t>(n)];
    EXPECT_LT(distance_to_deflected({x.x, x.y}, floor), 1e-9) << "floor node " << n;
  }
  EXPECT_EQ(mesh::summarize_quality(mesh::scaled_jacobians(moved.cells, moved.points)).inverted_cells, 0u);
}

}  // namespace
}  // namespace hotmesh::app
