// Tests of the forward_step sample (samples/forward_step, issue 45): a 2D channel with a
// forward-facing step drawn as CAD and meshed by gmsh (a node on every CAD vertex: the sharp
// foot, the fillet's ends), its metal solved by the real ccx, one sliding patch over the whole
// lower wall. run.sh runs ccx and the three cases; the one sliding wall converges, valid, every
// wall node on the deflected FEM wall (measured here against the CAD wall's own lines and arc
// plus ccx's printed displacements, not hotmesh's reconstruction), the foot held by its node
// from the start, no node across it; the wall split at the foot gives the same mesh; gmsh still
// makes the committed CAD and meshes, and the case names the wall's CAD edges.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <regex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "../geometry/curve_fixtures.hpp"
#include "calculix_runs.hpp"
#include "hotmesh/core/vec2.hpp"
#include "hotmesh/io/deflection_csv.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "run_command.hpp"
#include "sample_folder.hpp"
#include "test_support.hpp"

namespace hotmesh::samples {
namespace {

namespace fs = std::filesystem;
using geometry::Vec2;
using geometry::Vec3;
using test::shell_quote;

const fs::path kSample = fs::path(HOTMESH_SOURCE_DIR) / "samples" / "forward_step";
constexpr double kHeight = 10.0;  ///< the channel's height, mm

/// The lower wall as forward_step.geo draws it, by arc length s from the inlet (0, 0): the
/// floor to the foot (20, 0), the step's face to (20, 2), the fillet (radius 1 about (21, 2)) to
/// (21, 3), the step's top to the outlet (60, 3).
struct CadWall {
  static constexpr double kFoot = 20.0;                                 ///< s at the foot
  static constexpr double kFilletStart = 22.0;                          ///< s at (20, 2)
  static constexpr double kFilletEnd = kFilletStart + std::numbers::pi / 2;  ///< s at (21, 3)
  static constexpr double kEnd = kFilletEnd + 39.0;                     ///< s at (60, 3)

  static Vec2 at(double s) {
    if (s <= kFoot) return {s, 0.0};
    if (s <= kFilletStart) return {20.0, s - kFoot};
    if (s <= kFilletEnd) {
      const double a = std::numbers::pi - (s - kFilletStart);  // radius 1: the angle is the arc length
      return {21.0 + std::cos(a), 2.0 + std::sin(a)};
    }
    return {21.0 + (s - kFilletEnd), 3.0};
  }
  /// s of a point on the wall (within 1e-9).
  static double arc_length(const Vec2& p) {
    if (std::abs(p.y) < 1e-9 && p.x <= 20.0 + 1e-9) return p.x;
    if (std::abs(p.x - 20.0) < 1e-9 && p.y <= 2.0 + 1e-9) return kFoot + p.y;
    if (std::abs(p.y - 3.0) < 1e-9 && p.x >= 21.0 - 1e-9) return kFilletEnd + p.x - 21.0;
    const double a = std::atan2(p.y - 2.0, p.x - 21.0);
    EXPECT_NEAR(std::hypot(p.x - 21.0, p.y - 2.0), 1.0, 1e-9) << "(" << p.x << ", " << p.y << ") is not on the wall";
    return kFilletStart + std::numbers::pi - a;
  }
};

/// The deflected FEM wall: the CAD wall plus the FEM nodes' displacements interpolated linearly
/// along it, as the case's displacement form of degree 1 makes it (the CAD's lines are
/// parametrised by length, its arc of radius 1 by angle: both by s).
class DeflectedWall {
 public:
  explicit DeflectedWall(const geometry::DeflectionSamples& table) {
    for (std::size_t j = 0; j < table.size(); ++j) {
      nodes_.push_back({CadWall::arc_length({table.points[j].x, table.points[j].y}),
                        {table.deflections[j].x, table.deflections[j].y}});
    }
    std::sort(nodes_.begin(), nodes_.end(), [](const Node& a, const Node& b) { return a.s < b.s; });
  }
  std::size_t size() const { return nodes_.size(); }

  Vec2 displacement(double s) const {
    const auto after = std::upper_bound(nodes_.begin(), nodes_.end(), s, [](double v, const Node& n) { return v < n.s; });
    if (after == nodes_.begin()) return nodes_.front().u;
    if (after == nodes_.end()) return nodes_.back().u;
    const Node& a = *(after - 1);
    const Node& b = *after;
    return a.u + ((s - a.s) / (b.s - a.s)) * (b.u - a.u);
  }
  Vec2 at(double s) const { return CadWall::at(s) + displacement(s); }

  /// The distance of q from the deflected wall and the s of its nearest point, searched within
  /// `reach` of s0: samples 1e-3 mm apart, then golden sections about the best.
  std::pair<double, double> distance(const Vec2& q, double s0, double reach = 1.0) const {
    const double lo = std::max(0.0, s0 - reach), hi = std::min(CadWall::kEnd, s0 + reach);
    const geometry::test::BruteForce nearest = geometry::test::sampled_minimum(
        [&](double s) { return norm(at(s) - q); }, lo, hi, static_cast<int>(std::ceil((hi - lo) / 1e-3)));
    return {nearest.distance, nearest.parameter};
  }

 private:
  struct Node {
    double s;
    Vec2 u;
  };
  std::vector<Node> nodes_;
};

/// The committed sample in a temporary folder (run.sh writes beside its inputs).
struct ForwardStep : SampleFolder {
  ForwardStep() : SampleFolder("forward_step") {
    fs::create_directories(folder);
    for (const char* name : {"forward_step.step", "forward_step.msh", "forward_step-split.msh", "metal_mesh.inp", "metal.inp",
                             "forward_step.yaml", "forward_step-nofeatures.yaml", "forward_step-split.yaml", "run.sh"}) {
      fs::copy_file(kSample / name, folder / name);
    }
  }
};

TEST(ForwardStepSample, OneSlidingWallOverTheFootAndFilletFollowsTheFemWallAsTheSplitWallDoes) {
  if (!test::have_ccx()) GTEST_SKIP() << "ccx (Debian package calculix-ccx) is not installed; scripts/install-deps.sh installs it";
  const ForwardStep sample;
  const auto run = sample.run_script("run.sh");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  // hotmesh fem listed the wall's set; hotmesh check found each moved wall on its deflected CAD
  // wall, nodes to rounding and faces within 1e-3 of the channel height.
  EXPECT_THAT(run.output, ::testing::ContainsRegex("WALL +[0-9]+ nodes"));
  EXPECT_EQ(occurrences(run.output, "patches within the tolerance"), 3u) << run.output;

  const mesh::Mesh before = io::read_gmsh(sample.folder / "forward_step.msh");
  const mesh::Mesh one = sample.deformed("forward_step");
  const nlohmann::json report = sample.report("forward_step");
  EXPECT_EQ(report["status"], "success");
  EXPECT_EQ(report["inverted_cells"], 0);
  EXPECT_GT(report["min_scaled_jacobian"].get<double>(), 0.4);
  // The foot, a CAD vertex with a mesh node on it, is held by that node from the start; the
  // fillet's ends are no corners (the fillet is tangent to the face and the top).
  ASSERT_EQ(report["features"].size(), 1u) << report["features"].dump();
  const nlohmann::json& foot = report["features"][0];
  EXPECT_EQ(foot["held"], "from_start");
  EXPECT_NEAR(foot["angle_deg"].get<double>(), 90.0, 1.0);
  EXPECT_LT(foot["distance"].get<double>(), 1e-9);

  // The wall's table as hotmesh reads it from ccx's .frd (hotmesh fem) holds ccx's own printout
  // of the set (metal.dat, seven digits) to the .frd's six.
  const auto fem = test::run_command(std::string(HOTMESH_EXE) + " -q fem " + shell_quote((sample.folder / "metal.frd").string()) +
                                     " --inp " + shell_quote((sample.folder / "metal.inp").string()) + " --set WALL -o " +
                                     shell_quote((sample.folder / "wall.csv").string()));
  ASSERT_EQ(fem.exit_code, 0) << fem.output;
  const geometry::DeflectionSamples table = io::read_deflection_csv(sample.folder / "wall.csv");
  const auto printed = test::dat_displacements(test::read_text(sample.folder / "metal.dat"));
  ASSERT_EQ(printed.size(), 1u);
  ASSERT_EQ(table.size(), printed[0].size());
  ASSERT_EQ(table.ids.size(), table.size());
  double largest = 0.0;
  for (std::size_t j = 0; j < table.size(); ++j) {
    const Vec3& u = printed[0].at(table.ids[j]);
    EXPECT_LT(norm(table.deflections[j] - u), 1e-6) << table.label(j);
    largest = std::max(largest, norm(u));
  }
  EXPECT_NEAR(largest, 0.34, 0.01);  // as the deflections, up to 0.35 mm
  const DeflectedWall wall(table);

  // Every wall node on the deflected FEM wall, within 1e-3 of the channel height, and on its own
  // side of the foot; the node on the foot on the deflected foot.
  const auto* patch = before.find_patch("wall");
  ASSERT_NE(patch, nullptr);
  double worst = 0.0;
  Vec2 worst_at{};
  int on_foot = 0;
  for (const mesh::NodeId n : patch->nodes) {
    const Vec3& p = before.points[static_cast<std::size_t>(n)];
    const Vec3& q = one.points[static_cast<std::size_t>(n)];
    const double s0 = CadWall::arc_length({p.x, p.y});
    const auto [miss, s] = wall.distance({q.x, q.y}, s0);
    if (miss > worst) {
      worst = miss;
      worst_at = {p.x, p.y};
    }
    if (std::abs(s0 - CadWall::kFoot) < 1e-9) {
      ++on_foot;
      EXPECT_LT(norm(Vec2{q.x, q.y} - wall.at(CadWall::kFoot)), 1e-9);
    } else {
      EXPECT_EQ(s < CadWall::kFoot, s0 < CadWall::kFoot) << "node " << before.node_id(n) << " slid across the foot";
    }
  }
  EXPECT_EQ(on_foot, 1);
  std::printf("forward_step: the wall's nodes within %.3g mm of the deflected FEM wall, farthest the one from (%.6g, %.6g)\n",
              worst, worst_at.x, worst_at.y);
  EXPECT_LT(worst, 1e-3 * kHeight);

  // The paper's sliding alone converges too: the node on the foot still holds it.
  EXPECT_EQ(sample.report("forward_step-nofeatures")["status"], "success");
  EXPECT_EQ(sample.report("forward_step-nofeatures")["inverted_cells"], 0);

  // The wall split at the foot into two patches moves the mesh the same.
  const mesh::Mesh split = sample.deformed("forward_step-split");
  ASSERT_EQ(split.node_count(), one.node_count());
  double apart = 0.0;
  for (std::size_t n = 0; n < one.node_count(); ++n) apart = std::max(apart, distance(one.points[n], split.points[n]));
  std::printf("forward_step: one sliding wall and the wall split at the foot %.3g mm apart at most\n", apart);
  EXPECT_LT(apart, 1e-8);
}

/// gmsh in `folder`, writing `output` there (the .inp names the file it was written as).
test::CommandResult gmsh(const fs::path& folder, const std::string& arguments, const std::string& output) {
  return test::run_command("cd " + shell_quote(folder.string()) + " && gmsh -nt 1 " + arguments + " " +
                           shell_quote((kSample / "forward_step.geo").string()) + " -o " + output + " 2>&1");
}

TEST(ForwardStepSample, GmshMakesTheCommittedCadAndMeshesAndTheCasesNameTheWallsEdges) {
  const test::TempDir dir;
  for (const auto& [arguments, output] : std::vector<std::pair<std::string, std::string>>{
           {"-0", "forward_step.step"},
           {"-2 -format msh41", "forward_step.msh"},
           {"-2 -setnumber split 1 -format msh41", "forward_step-split.msh"},
           {"-2 -setnumber part 1 -format inp", "metal_gmsh.inp"}}) {
    const auto r = gmsh(dir.path(), arguments, output);
    ASSERT_EQ(r.exit_code, 0) << "gmsh is a required test dependency (scripts/install-deps.sh):\n" << r.output;
    // The STEP file's header has the time it was written.
    const std::regex stamp("'[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9:]{8}'");
    EXPECT_EQ(std::regex_replace(test::read_text(dir / output), stamp, "''"),
              std::regex_replace(test::read_text(kSample / output), stamp, "''"))
        << output << " is not what gmsh makes of forward_step.geo";
  }
  // The cases' edges 1 (the floor) and 2, 3, 4 (the step's face, the fillet, its top) are the
  // lower wall's, as hotmesh cad lists them.
  const auto listing = test::run_command(std::string(HOTMESH_EXE) + " -q cad --json --unit mm " +
                                         shell_quote((kSample / "forward_step.step").string()));
  ASSERT_EQ(listing.exit_code, 0) << listing.output;
  const nlohmann::json cad = nlohmann::json::parse(listing.output.substr(listing.output.find('{')));
  const std::vector<std::pair<Vec2, Vec2>> wall{{{0, 0}, {20, 0}}, {{20, 0}, {20, 2}}, {{20, 2}, {21, 3}}, {{21, 3}, {60, 3}}};
  for (std::size_t k = 0; k < wall.size(); ++k) {
    const nlohmann::json& edge = cad["edges"][k];
    EXPECT_EQ(edge["id"], static_cast<int>(k) + 1);
    const Vec2 start{edge["start"][0].get<double>(), edge["start"][1].get<double>()};
    const Vec2 end{edge["end"][0].get<double>(), edge["end"][1].get<double>()};
    const auto [a, b] = wall[k];
    EXPECT_LT(std::min(norm(start - a) + norm(end - b), norm(start - b) + norm(end - a)), 1e-9) << edge.dump();
  }
  EXPECT_EQ(cad["edges"][2]["kind"], "circle");
  for (const char* name : {"forward_step.yaml", "forward_step-nofeatures.yaml"}) {
    EXPECT_THAT(test::read_text(kSample / name), ::testing::HasSubstr("edges: [1, 2, 3, 4]")) << name;
  }
}

}  // namespace
}  // namespace hotmesh::samples
