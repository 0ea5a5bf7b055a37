// End-to-end tests of `hotmesh deform` on sliding walls whose corners lie on mesh nodes (issue
// 45): walls drawn as CAD and meshed by gmsh, which puts a node on every CAD vertex and a row of
// nodes along every CAD edge, as every mesher working from CAD does. Such a node cannot slide:
// the wall has no tangent there, and Newton alternated between its sides for ever. It holds its
// corner from the start, and the nodes either side slide on their own segments, so one sliding
// patch over the corners moves the mesh as the same wall split into patches at them does.
//
// 2D: a channel whose lower wall has concave and convex corners of 63, 90 and 127 degrees
// (tests/data/gmsh/corner_channel.geo), an FEM table of its nodes every 0.3 mm with a deflection
// that moves, stretches and turns every piece of it. With a linear table the deflected wall is
// the polyline through the deflected FEM nodes, computed here.
// 3D: a duct whose floor has a forward-facing step, three plane CAD faces meeting at a concave
// and a convex edge (tests/data/gmsh/step_duct.geo), moved by an affine deflection that keeps
// every face a plane, so the deflected faces and edges are known exactly.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "channel_step.hpp"
#include "deform_cases.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::app {
namespace {

using geometry::Vec2;
using geometry::Vec3;
using test::hotmesh;
using test::read_json;
using test::shell_quote;

/// gmsh meshes tests/data/gmsh/<geo> into `out` with the given -setnumber settings.
void gmsh(const std::string& geo, int dimension, const std::string& settings, const std::filesystem::path& out) {
  const auto r = test::run_command(fmt::format("gmsh -{} -nt 1 {} {} -format msh41 -o {}", dimension, settings,
                                               shell_quote(test::data_path("gmsh/" + geo).string()),
                                               shell_quote(out.string())));
  ASSERT_EQ(r.exit_code, 0) << "gmsh is a required test dependency (scripts/install-deps.sh):\n" << r.output;
}

/// A run of `hotmesh deform`: the command's result, its report, the mesh before and after.
struct DeformRun {
  test::CommandResult result;
  nlohmann::json report;
  mesh::Mesh before;
  mesh::Mesh after;
};

DeformRun deform(const std::filesystem::path& dir, const std::string& case_text, const std::string& mesh_file) {
  test::write_text(dir / "case.yaml", case_text);
  DeformRun r;
  const auto out = dir / "out";
  std::filesystem::remove_all(out);
  r.result = hotmesh("deform " + shell_quote((dir / "case.yaml").string()) + " -o " + shell_quote(out.string()));
  if (r.result.exit_code != 0) return r;
  r.report = read_json(out / "report.json");
  r.before = io::read_gmsh(dir / mesh_file);
  r.after = io::read_gmsh(out / "deformed.msh");
  return r;
}

double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t = std::clamp(dot(p - a, ab) / dot(ab, ab), 0.0, 1.0);
  return norm(p - (a + t * ab));
}

// ---- 2D: the channel's lower wall -------------------------------------------------------------

/// The lower wall's CAD vertices (corner_channel.geo): its ends and seven corners between them.
const std::vector<Vec2> kFloor{{0, 0}, {4, 0}, {4, 1}, {6, 1}, {6.5, 2}, {7, 1}, {9, 1}, {9, 0}, {14, 0}};

/// The FEM deflection, mm: a lift of 0.35 in the middle, a shift growing with height (the step
/// faces lean, the ridge widens), and a tilt; every corner moves and turns.
Vec2 deflection(const Vec2& x) {
  const double s = std::sin(std::numbers::pi * x.x / 14.0);
  return {0.15 * s * (1.0 + x.y), 0.35 * s * s + 0.1 * x.y * x.x / 14.0};
}

/// The FEM nodes of piece k of the wall (from vertex k to k + 1), about 0.3 mm apart, ends
/// included: a node on every vertex, as an FEM mesh from the same CAD has.
std::vector<Vec2> fem_nodes(std::size_t k) {
  const Vec2 a = kFloor[k], b = kFloor[k + 1];
  const int n = std::max(1, static_cast<int>(std::lround(norm(b - a) / 0.3)));
  std::vector<Vec2> nodes;
  for (int i = 0; i <= n; ++i) nodes.push_back(a + (static_cast<double>(i) / n) * (b - a));
  return nodes;
}

std::string table(const std::vector<Vec2>& nodes) {
  std::string text = "x,y,dx,dy\n";
  for (const Vec2& x : nodes) {
    const Vec2 d = deflection(x);
    text += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g}\n", x.x, x.y, d.x, d.y);
  }
  return text;
}

/// The piece of the undeformed wall that holds p (its index), or -1 for a vertex.
int piece_of(const Vec2& p) {
  for (std::size_t k = 0; k < kFloor.size(); ++k) {
    if (norm(p - kFloor[k]) < 1e-9) return -1;
  }
  for (std::size_t k = 0; k + 1 < kFloor.size(); ++k) {
    if (distance_to_segment(p, kFloor[k], kFloor[k + 1]) < 1e-9) return static_cast<int>(k);
  }
  ADD_FAILURE() << "(" << p.x << ", " << p.y << ") is not on the lower wall";
  return -2;
}

/// The piece of the deflected wall nearest q, and how far q is from it. Piece k is the
/// polyline through its FEM nodes deflected (a linear table).
std::pair<int, double> on_deflected_wall(const Vec2& q) {
  std::pair<int, double> best{-1, std::numeric_limits<double>::infinity()};
  for (std::size_t k = 0; k + 1 < kFloor.size(); ++k) {
    const std::vector<Vec2> nodes = fem_nodes(k);
    for (std::size_t j = 0; j + 1 < nodes.size(); ++j) {
      const double d = distance_to_segment(q, nodes[j] + deflection(nodes[j]), nodes[j + 1] + deflection(nodes[j + 1]));
      if (d < best.second) best = {static_cast<int>(k), d};
    }
  }
  return best;
}

class CornerChannel : public ::testing::Test {
 protected:
  /// The channel meshed by gmsh (split: one patch per piece of the lower wall), moved with
  /// inlet, outlet and top fixed and the lower wall sliding over its table(s); `floor_extra`
  /// added to each lower-wall patch's entry.
  DeformRun run(bool split, bool triangles, const std::string& floor_extra = "") {
    const std::string mesh_file = fmt::format("channel-{:d}-{:d}.msh", split, triangles);
    gmsh("corner_channel.geo", 2, fmt::format("-setnumber split {:d} -setnumber triangles {:d}", split, triangles),
         dir_ / mesh_file);
    std::string patches = "  inlet: {role: fixed}\n  outlet: {role: fixed}\n  top: {role: fixed}\n";
    std::vector<Vec2> all;
    for (std::size_t k = 0; k + 1 < kFloor.size(); ++k) {
      const std::vector<Vec2> nodes = fem_nodes(k);
      all.insert(all.end(), nodes.begin() + (k == 0 ? 0 : 1), nodes.end());
      if (!split) continue;
      test::write_text(dir_ / fmt::format("floor_{}.csv", k + 1), table(nodes));
      patches += fmt::format("  floor_{0}: {{role: sliding, deflection: {{file: floor_{0}.csv}}{1}}}\n", k + 1, floor_extra);
    }
    if (!split) {
      test::write_text(dir_ / "floor.csv", table(all));
      patches += fmt::format("  floor: {{role: sliding, deflection: {{file: floor.csv}}{}}}\n", floor_extra);
    }
    return deform(dir_.path(), fmt::format("mesh: {}\nlength_unit: mm\npatches:\n{}", mesh_file, patches), mesh_file);
  }

  /// Every lower-wall node ends on the deflected wall, on its own piece (a node on a vertex on
  /// that vertex deflected), and no cell is worse than `worst`.
  static void expect_on_the_deflected_wall(const DeformRun& r, double worst) {
    ASSERT_EQ(r.result.exit_code, 0) << r.result.output;
    EXPECT_EQ(r.report["inverted_cells"], 0);
    EXPECT_GE(r.report["min_scaled_jacobian"].get<double>(), worst);
    std::size_t on_vertices = 0;
    for (const mesh::Patch& patch : r.before.patches) {
      if (!patch.name.starts_with("floor")) continue;
      for (const mesh::NodeId n : patch.nodes) {
        const Vec3& x = r.before.points[static_cast<std::size_t>(n)];
        const Vec3& y = r.after.points[static_cast<std::size_t>(n)];
        const Vec2 p{x.x, x.y}, q{y.x, y.y};
        const int piece = piece_of(p);
        if (piece == -1) {
          ++on_vertices;
          EXPECT_LT(norm(q - (p + deflection(p))), 1e-9) << "the node on the vertex (" << p.x << ", " << p.y << ")";
          continue;
        }
        const auto [nearest, miss] = on_deflected_wall(q);
        EXPECT_LT(miss, 1e-9) << "node " << r.before.node_id(n);
        EXPECT_EQ(nearest, piece) << "node " << r.before.node_id(n) << " slid across a corner";
      }
    }
    EXPECT_EQ(on_vertices, split_vertices(r) ? 2 * (kFloor.size() - 2) + 2 : kFloor.size());
  }

  /// With the wall split, a vertex node lies on two patches and is counted on each.
  static bool split_vertices(const DeformRun& r) { return r.before.find_patch("floor") == nullptr; }

  test::TempDir dir_;
};

TEST_F(CornerChannel, OneSlidingWallOverCornersOnNodesConvergesAndHoldsThem) {
  const DeformRun r = run(false, false);
  expect_on_the_deflected_wall(r, 0.5);
  // The seven corners, each held from the start by the node on its vertex.
  std::vector<int> held;
  for (const auto& f : r.report["features"]) {
    EXPECT_EQ(f["held"], "from_start");
    EXPECT_LT(f["distance"].get<double>(), 1e-12);
    held.push_back(static_cast<int>(std::lround(f["angle_deg"].get<double>())));
  }
  std::sort(held.begin(), held.end());
  EXPECT_EQ(held.size(), 7u);
  EXPECT_GE(held.back(), 127);  // the ridge's tip turns by 127 degrees undeformed, more deflected
}

TEST_F(CornerChannel, OneSlidingWallMovesTheMeshAsTheWallSplitAtItsCorners) {
  const DeformRun one = run(false, false);
  const DeformRun split = run(true, false);
  ASSERT_EQ(one.result.exit_code, 0) << one.result.output;
  ASSERT_EQ(split.result.exit_code, 0) << split.result.output;
  expect_on_the_deflected_wall(split, 0.5);
  ASSERT_EQ(one.after.node_count(), split.after.node_count());
  double largest = 0.0;
  for (std::size_t n = 0; n < one.after.node_count(); ++n) largest = std::max(largest, distance(one.after.points[n], split.after.points[n]));
  EXPECT_LT(largest, 1e-8);  // 14 mm long: the same mesh but for rounding
}

TEST_F(CornerChannel, WithoutFeaturesTheNodesOnCornersHoldThemToo) {
  // `features: off` leaves corners between nodes to the paper's sliding; a node on a corner
  // still cannot slide.
  expect_on_the_deflected_wall(run(false, false, ", features: off"), 0.5);
}

TEST_F(CornerChannel, TrianglesHoldTheirCornersAsQuadsDo) { expect_on_the_deflected_wall(run(false, true), 0.5); }

TEST(CornerOnANodeTheTableMisses, KeepsTheMotionsMeshWhenTheCornerPassWouldRuinIt) {
  // The channel with a forward-facing step of channel_step.geo, its lower wall on its CAD edges,
  // but an FEM table every 1.3 mm of the wall that has no node on the step's foot. With
  // `form: curve` the deflected wall is the polyline through the deflected FEM nodes: it cuts
  // the foot with two kinks of its own, within a cell of the node that holds the CAD's foot.
  // Holding them all would squash that cell to nothing (0.000 before): the corner pass is
  // undone, with a note that says why and what to do, and the motion's mesh stands.
  // `form: displacement` keeps the CAD's foot and has no such kinks.
  const test::ChannelStep channel;
  const double length = 10.0 + 3.0 + 0.5 * std::numbers::pi * test::StepWall::kRadius + 13.0;
  std::string table = "x,y,dx,dy\n";
  for (double s = 0.0; s < length + 0.65; s += 1.3) {
    const Vec2 p = test::StepWall::at(std::min(s, length));
    table += fmt::format("{:.17g},{:.17g},0,0.35\n", p.x, p.y);
  }
  test::write_text(channel.dir() / "coarse.csv", table);
  for (const std::string form : {"curve", "displacement"}) {
    SCOPED_TRACE(form);
    channel.write_case(fmt::format("{{role: sliding, deflection: {{file: coarse.csv, edges: [{}], form: {}}}}}",
                                   channel.wall_edge_list(), form));
    const auto r = hotmesh("deform " + shell_quote(channel.path("case.yaml")) + " -o " + shell_quote(channel.path("out")));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto report = read_json(channel.dir() / "out" / "report.json");
    EXPECT_GT(report["min_scaled_jacobian"].get<double>(), 0.3);
    const bool undone = r.output.find("the corner pass was undone") != std::string::npos;
    EXPECT_EQ(undone, form == "curve") << r.output;
    if (undone) {
      EXPECT_THAT(r.output, ::testing::HasSubstr("give it a node there, or take form: displacement"));
    }
  }
}

// ---- 3D: the duct's stepped floor -------------------------------------------------------------

/// The FEM deflection of the floor, mm: affine, so every plane face stays a plane: a lift
/// rising along the duct, and a shear that leans the step's face forward.
constexpr double kLift = 0.1, kRise = 0.02, kLean = 0.08;
Vec3 floor_deflection(const Vec3& x) { return {kLean * x.y, kLift + kRise * x.x, 0.0}; }

/// The floor's faces (step_duct.geo): 0 the floor before the step (y = 0, x <= 5), 1 the step's
/// face (x = 5), 2 the floor after it (y = 1, x >= 5); the faces a point lies on.
std::vector<int> floor_faces(const Vec3& x) {
  std::vector<int> faces;
  if (std::abs(x.y) < 1e-9 && x.x <= 5.0 + 1e-9) faces.push_back(0);
  if (std::abs(x.x - 5.0) < 1e-9 && x.y >= -1e-9 && x.y <= 1.0 + 1e-9) faces.push_back(1);
  if (std::abs(x.y - 1.0) < 1e-9 && x.x >= 5.0 - 1e-9) faces.push_back(2);
  return faces;
}

/// How far q is from face k deflected (a plane: its undeformed plane's points moved affinely).
double off_deflected_face(int k, const Vec3& q) {
  // Each deflected face is the plane through the deflected images of three of its points.
  static const std::array<std::array<Vec3, 3>, 3> corners{{{{{0, 0, 0}, {5, 0, 0}, {0, 0, 3}}},
                                                           {{{5, 0, 0}, {5, 1, 0}, {5, 0, 3}}},
                                                           {{{5, 1, 0}, {12, 1, 0}, {5, 1, 3}}}}};
  const auto& c = corners[static_cast<std::size_t>(k)];
  std::array<Vec3, 3> moved;
  for (std::size_t i = 0; i < 3; ++i) moved[i] = c[i] + floor_deflection(c[i]);
  Vec3 normal = cross(moved[1] - moved[0], moved[2] - moved[0]);
  normal = normal / norm(normal);
  return std::abs(dot(q - moved[0], normal));
}

class StepDuct : public ::testing::Test {
 protected:
  /// The duct meshed by gmsh and written to STEP by it, moved with the floor sliding over its
  /// three CAD faces (`floor_extra` added to its entry), inlet, outlet and sides slipping, the
  /// top fixed.
  DeformRun run(bool tets, const std::string& floor_extra = "") {
    gmsh("step_duct.geo", 3, fmt::format("-setnumber tets {:d}", tets), dir_ / "duct.msh");
    const auto cad = test::run_command("gmsh -0 " + shell_quote(test::data_path("gmsh/step_duct.geo").string()) + " -o " +
                                       shell_quote((dir_ / "duct.step").string()));
    EXPECT_EQ(cad.exit_code, 0) << cad.output;
    write_table();
    return deform(dir_.path(),
                  fmt::format("mesh: duct.msh\ncad: duct.step\nlength_unit: mm\npatches:\n"
                              "  floor: {{role: sliding, deflection: {{file: floor.csv, faces: [{}]}}{}}}\n"
                              "  inlet: {{role: slip}}\n  outlet: {{role: slip}}\n  top: {{role: fixed}}\n"
                              "  front: {{role: slip}}\n  back: {{role: slip}}\n",
                              fmt::join(floor_cad_faces(), ", "), floor_extra),
                  "duct.msh");
  }

  /// Every floor node ends on its own face deflected, those on an edge on both its faces; no
  /// cell worse than `worst`.
  static void expect_on_the_deflected_floor(const DeformRun& r, double worst) {
    ASSERT_EQ(r.result.exit_code, 0) << r.result.output;
    EXPECT_EQ(r.report["inverted_cells"], 0);
    EXPECT_GE(r.report["min_scaled_jacobian"].get<double>(), worst);
    std::size_t on_edges = 0;
    for (const mesh::NodeId n : r.before.find_patch("floor")->nodes) {
      const Vec3& x = r.before.points[static_cast<std::size_t>(n)];
      const Vec3& q = r.after.points[static_cast<std::size_t>(n)];
      const std::vector<int> faces = floor_faces(x);
      ASSERT_FALSE(faces.empty()) << "node " << r.before.node_id(n) << " is not on the floor";
      if (faces.size() > 1) ++on_edges;
      for (const int k : faces) EXPECT_LT(off_deflected_face(k, q), 1e-9) << "node " << r.before.node_id(n) << ", face " << k;
      // None slid across an edge: it stays on its side of each edge it is not on.
      const Vec3 foot = Vec3{5, 0, 0} + floor_deflection({5, 0, 0}), shoulder = Vec3{5, 1, 0} + floor_deflection({5, 1, 0});
      if (faces == std::vector<int>{0}) {
        EXPECT_LT(q.x, foot.x) << "node " << r.before.node_id(n);
      }
      if (faces == std::vector<int>{2}) {
        EXPECT_GT(q.x, shoulder.x) << "node " << r.before.node_id(n);
      }
      if (faces == std::vector<int>{1}) {
        EXPECT_GT(q.y, foot.y);
        EXPECT_LT(q.y, shoulder.y);
      }
    }
    EXPECT_GT(on_edges, 10u);
  }

 private:
  /// The floor's faces in duct.step, from `hotmesh cad`: gmsh numbers them, not this test.
  /// OpenCASCADE's bounding boxes are widened by the faces' tolerance.
  std::vector<int> floor_cad_faces() const {
    constexpr double kBox = 1e-3;
    const auto listing = hotmesh("cad --json --unit mm " + shell_quote((dir_ / "duct.step").string()));
    EXPECT_EQ(listing.exit_code, 0) << listing.output;
    std::vector<int> ids;
    const nlohmann::json model = nlohmann::json::parse(listing.output.substr(listing.output.find('{')));
    for (const auto& face : model["faces"]) {
      const auto& low = face["bounds"]["min"];
      const auto& high = face["bounds"]["max"];
      const bool spans_width = low[2].get<double>() < kBox && high[2].get<double>() > 3.0 - kBox;
      if (spans_width && high[1].get<double>() <= 1.0 + kBox) ids.push_back(face["id"].get<int>());
    }
    EXPECT_EQ(ids.size(), 3u) << listing.output;
    return ids;
  }

  /// The FEM nodes: a 0.25 mm grid on each face, edges included.
  void write_table() const {
    std::vector<Vec3> nodes;
    for (int k = 0; k <= 12; ++k) {
      const double z = 0.25 * k;
      for (int i = 0; i <= 20; ++i) nodes.push_back({0.25 * i, 0.0, z});
      for (int j = 1; j < 4; ++j) nodes.push_back({5.0, 0.25 * j, z});
      for (int i = 0; i <= 28; ++i) nodes.push_back({5.0 + 0.25 * i, 1.0, z});
    }
    std::string text = "x,y,z,dx,dy,dz\n";
    for (const Vec3& x : nodes) {
      const Vec3 d = floor_deflection(x);
      text += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", x.x, x.y, x.z, d.x, d.y, d.z);
    }
    test::write_text(dir_ / "floor.csv", text);
  }

  test::TempDir dir_;
};

TEST_F(StepDuct, AFloorWithAStepEdgeAlongARowOfNodesConverges) {
  const DeformRun r = run(false);
  expect_on_the_deflected_floor(r, 0.4);
  std::size_t creases = 0;
  for (const auto& f : r.report["features"]) {
    if (f["kind"] != "crease") continue;
    ++creases;
    EXPECT_EQ(f["held"], "from_start");
    EXPECT_LT(f["distance"].get<double>(), 1e-9);
  }
  EXPECT_EQ(creases, 2u);  // the step's foot and shoulder
}

TEST_F(StepDuct, WithoutFeaturesTheNodesOnTheStepsEdgesHoldThemToo) { expect_on_the_deflected_floor(run(false, ", features: off"), 0.4); }

TEST_F(StepDuct, TetrahedraHoldTheStepsEdgesAsHexahedraDo) { expect_on_the_deflected_floor(run(true), 0.2); }

}  // namespace
}  // namespace hotmesh::app
