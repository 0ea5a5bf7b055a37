// End-to-end tests of `hotmesh deform` on a wall of trimmed CAD faces (issue 23): the fluid over
// a 10 x 10 x 2 mm plate with a round hole of radius 2, meshed with tetrahedra by gmsh and
// written to STEP by gmsh's OpenCASCADE kernel (tests/data/gmsh/plate_hole_fluid.geo). The wall
// is the plate's top face, the plane z = 2 trimmed by the hole's circle, and the hole's wall
// below that circle, one sliding patch on those CAD faces. The FEM table moves the whole wall by
// a rigid shift (a, b) in the plate's plane and lifts it by a radial bulge, so the deflected
// hole is the undeformed one shifted sideways: its footprint on the deflected top face is the
// disc of radius 2 about (a, b). The nodes must end on the deflected faces and, on the top
// face, inside its trimmed region: none on the plane's continuation over the hole.
//
// The tests compare each node with the wall computed here: a point q of the deflected wall is
// p + d(p) for a point p of the undeformed wall, and the shift is rigid, so p has the
// x, y of q less the shift; its radius says which face p is on and its z follows.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "deform_cases.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::app {
namespace {

using ::testing::HasSubstr;
using geometry::Vec3;
using test::hotmesh;
using test::read_json;
using test::shell_quote;

constexpr double kBulge = 0.15;  // the lift at the hole's axis, mm
constexpr double kHole = 2.0;    // radius of the hole at the top face
constexpr double kTop = 2.0;     // z of the top face

/// The lift of the top face at radius r from the hole's axis: a bulge, flat at the axis, falling
/// to nothing at the box's corners.
double bulge(double r) { return kBulge * std::pow(std::cos(std::numbers::pi * r / 14.0), 2); }

/// The plate's hole (plate_hole_fluid.geo): a cylinder of radius 2 (cone_deg = 0), or a
/// countersink: a cone at cone_deg to the plate from radius 2 at the top down to radius 1, then
/// a cylinder of radius 1; and the wall's rigid shift in the plate's plane, mm.
struct Hole {
  double cone_deg = 0.0;
  double shift_x = 0.0;
  double shift_y = 0.0;
  double slope() const { return std::tan(cone_deg * std::numbers::pi / 180.0); }
  double bore() const { return cone_deg > 0.0 ? 1.0 : kHole; }                   ///< the cylinder's radius
  double bore_top() const { return cone_deg > 0.0 ? kTop - slope() : kTop; }  ///< where the cylinder ends
  /// z of the undeformed cone at radius r.
  double cone_z(double r) const { return kTop - (kHole - r) * slope(); }
  /// The FEM deflection: the shift, and the bulge scaled down with z through the hole (nothing
  /// at the hole's end z = 0, which slips in its plane). Constant round the axis on the hole's
  /// faces, so the fields fitted there are exact round it.
  Vec3 deflection(const Vec3& x) const { return {shift_x, shift_y, bulge(std::hypot(x.x, x.y)) * x.z / kTop}; }
  /// The radius about the deflected hole's axis of a point of the deflected wall: that of its
  /// undeformed point.
  double radius(const Vec3& q) const { return std::hypot(q.x - shift_x, q.y - shift_y); }
};

/// How far `q` is from the deflected wall (vertically on the top face and the cone, radially on
/// the cylinder): the least of its misses from each face whose trimmed region holds it. The top
/// face holds the points outside the hole's circle only; the hole's faces those inside it.
double off_wall(const Hole& hole, const Vec3& q) {
  constexpr double kOnRim = 1e-9;
  const double r = hole.radius(q);
  double miss = std::numeric_limits<double>::infinity();
  if (r >= kHole - kOnRim) miss = std::min(miss, std::abs(q.z - (kTop + bulge(r))));  // the top face
  if (hole.cone_deg > 0.0 && r <= kHole + kOnRim && r >= hole.bore() - kOnRim) {  // the cone
    const double z = hole.cone_z(r);
    miss = std::min(miss, std::abs(q.z - (z + bulge(r) * z / kTop)));
  }
  const double z = q.z / (1.0 + bulge(hole.bore()) / kTop);  // the undeformed z on the cylinder
  if (z >= -kOnRim && z <= hole.bore_top() + kOnRim) miss = std::min(miss, std::abs(r - hole.bore()));
  return miss;
}

/// Which face of the undeformed wall a node starts on.
enum class Start { top, rim, hole };

struct WallNode {
  Start start;
  Vec3 before;
  Vec3 after;
};

struct DeformRun {
  test::CommandResult result;
  std::filesystem::path out;
  nlohmann::json report;
  std::vector<WallNode> wall;  ///< the wall patch's nodes
  mesh::QualitySummary quality;
};

/// The plate's fluid in a temporary folder: fluid.msh and fluid.step by gmsh, the FEM table
/// wall.csv, and the numbers of the wall's CAD faces in fluid.step.
class TrimmedPlate {
 public:
  explicit TrimmedPlate(const Hole& hole) : hole_(hole) {
    const std::string geo = shell_quote(test::data_path("gmsh/plate_hole_fluid.geo").string());
    const std::string cone = fmt::format("-setnumber cone_deg {} ", hole.cone_deg);
    const auto meshed = test::run_command("gmsh -3 -nt 1 " + cone + geo + " -format msh41 -o " +
                                        shell_quote((dir_ / "fluid.msh").string()));
    EXPECT_EQ(meshed.exit_code, 0) << "gmsh is a required test dependency (scripts/install-deps.sh):\n"
                                   << meshed.output;
    const auto cad = test::run_command("gmsh -0 " + cone + geo + " -o " + shell_quote((dir_ / "fluid.step").string()));
    EXPECT_EQ(cad.exit_code, 0) << cad.output;
    find_wall_faces();
    write_table();
  }

  const Hole& hole() const { return hole_; }
  const std::vector<int>& wall_faces() const { return faces_; }

  /// `hotmesh deform` with the wall sliding on its faces (`wall_extra` added to its entry), the
  /// hole's end and the box's sides slipping, the ceiling fixed; `solver` the case's solver
  /// map, if any.
  DeformRun deform(const std::string& wall_extra = "", const std::string& solver = "") const {
    test::write_text(dir_ / "case.yaml",
                     fmt::format("mesh: fluid.msh\ncad: fluid.step\nlength_unit: mm\n{}patches:\n"
                                 "  wall: {{role: sliding, deflection: {{file: wall.csv, faces: [{}], degree: 3}}{}}}\n"
                                 "  hole_end: {{role: slip}}\n  ceiling: {{role: fixed}}\n"
                                 "  side_xmin: {{role: slip}}\n  side_xmax: {{role: slip}}\n"
                                 "  side_ymin: {{role: slip}}\n  side_ymax: {{role: slip}}\n",
                                 solver.empty() ? "" : "solver: " + solver + "\n", fmt::join(faces_, ", "), wall_extra));
    DeformRun r;
    r.out = dir_ / "out";
    std::filesystem::remove_all(r.out);
    r.result = hotmesh("deform " + shell_quote((dir_ / "case.yaml").string()) + " -o " + shell_quote(r.out.string()));
    if (r.result.exit_code != 0) return r;
    r.report = read_json(r.out / "report.json");
    const mesh::Mesh before = io::read_gmsh(dir_ / "fluid.msh");
    const mesh::Mesh after = io::read_gmsh(r.out / "deformed.msh");
    r.quality = mesh::summarize_quality(mesh::scaled_jacobians(after.cells, after.points));
    for (const mesh::NodeId n : before.find_patch("wall")->nodes) {
      const Vec3& x = before.points[static_cast<std::size_t>(n)];
      const bool on_top = std::abs(x.z - kTop) < 1e-9, on_circle = std::abs(std::hypot(x.x, x.y) - kHole) < 1e-9;
      const Start start = on_top ? (on_circle ? Start::rim : Start::top) : Start::hole;
      r.wall.push_back({start, x, after.points[static_cast<std::size_t>(n)]});
    }
    return r;
  }

 private:
  /// The plate's top face (the plane at z = 2) and the hole's faces (below it, above z = 0),
  /// from `hotmesh cad`'s listing: gmsh numbers the faces, not this test.
  void find_wall_faces() {
    const auto listing = hotmesh("cad --json --unit mm " + shell_quote((dir_ / "fluid.step").string()));
    ASSERT_EQ(listing.exit_code, 0) << listing.output;
    const auto faces = nlohmann::json::parse(listing.output.substr(listing.output.find('{')))["faces"];
    for (const auto& face : faces) {
      const double low = face["bounds"]["min"][2].get<double>(), high = face["bounds"]["max"][2].get<double>();
      const bool top = std::abs(low - kTop) < 1e-9 && std::abs(high - kTop) < 1e-9;
      const bool in_hole = high <= kTop + 1e-9 && high > 1e-9 && low < kTop - 1e-9;
      if (top || in_hole) faces_.push_back(face["id"].get<int>());
    }
    ASSERT_EQ(faces_.size(), hole_.cone_deg > 0.0 ? 3u : 2u) << listing.output;
  }

  /// The FEM nodes: a 0.5 mm grid over the top face outside radius 2.2, and 32 columns round
  /// the hole (at five heights on the cylinder; on the countersink, five radii on the cone and
  /// four heights on the cylinder below it).
  void write_table() const {
    std::vector<Vec3> nodes;
    for (int i = 0; i <= 20; ++i) {
      for (int j = 0; j <= 20; ++j) {
        const Vec3 x{-5.0 + 0.5 * i, -5.0 + 0.5 * j, kTop};
        if (std::hypot(x.x, x.y) >= 2.2) nodes.push_back(x);
      }
    }
    for (int k = 0; k < 32; ++k) {
      const double a = 2.0 * std::numbers::pi * k / 32.0, c = std::cos(a), s = std::sin(a);
      if (hole_.cone_deg > 0.0) {
        for (const double r : {2.0, 1.75, 1.5, 1.25, 1.0}) nodes.push_back({r * c, r * s, hole_.cone_z(r)});
        for (int i = 0; i < 4; ++i) nodes.push_back({c, s, hole_.bore_top() * i / 4.0});
      } else {
        for (int i = 0; i <= 4; ++i) nodes.push_back({kHole * c, kHole * s, 0.5 * i});
      }
    }
    std::string table = "x,y,z,dx,dy,dz\n";
    for (const Vec3& x : nodes) {
      const Vec3 d = hole_.deflection(x);
      table += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", x.x, x.y, x.z, d.x, d.y, d.z);
    }
    test::write_text(dir_ / "wall.csv", table);
  }

  test::TempDir dir_;
  Hole hole_;
  std::vector<int> faces_;
};

/// Common checks of a successful run: no inverted cell, the sliding nodes on the deflected
/// faces (report.json), and every wall node on the deflected wall as computed here, on the top
/// face only outside the hole's circle. The tolerance is the fits' accuracy: the bulge is no
/// polynomial, and beyond the box's sides (where the shift takes the sides' nodes) the top
/// face's field is extrapolated (2e-4 at most measured); a node on the top plane's continuation
/// over a countersink is 0.05 to 0.14 above the cone.
void expect_on_trimmed_wall(const Hole& hole, const DeformRun& r, double min_quality) {
  EXPECT_EQ(r.report["status"], "success");
  EXPECT_EQ(r.report["inverted_cells"], 0);
  EXPECT_EQ(r.quality.inverted_cells, 0u);
  EXPECT_GT(r.quality.min_scaled_jacobian, min_quality);
  EXPECT_NEAR(r.report["min_scaled_jacobian"].get<double>(), r.quality.min_scaled_jacobian, 1e-12);
  EXPECT_LT(r.report["final_projection_distance"].get<double>(), 1e-7);
  double worst = 0.0;
  int off = 0;
  for (const WallNode& n : r.wall) {
    const double miss = off_wall(hole, n.after);
    worst = std::max(worst, miss);
    if (miss > 5e-4 && off++ < 5) {
      ADD_FAILURE() << "wall node from (" << n.before.x << ", " << n.before.y << ", " << n.before.z << ") at ("
                    << n.after.x << ", " << n.after.y << ", " << n.after.z << "), radius " << hole.radius(n.after)
                    << " about the deflected hole's axis, is " << miss << " off the deflected wall";
    }
  }
  EXPECT_EQ(off, 0) << "of " << r.wall.size() << " wall nodes; the worst " << worst << " off";
  ::testing::Test::RecordProperty("min_scaled_jacobian", fmt::format("{:.4f}", r.quality.min_scaled_jacobian));
  ::testing::Test::RecordProperty("worst_wall_node_off_wall", fmt::format("{:.3g}", worst));
}

// The cylindrical hole, the wall shifted by (0.3, 0.1): the wall turns by 90 degrees at the
// circle, a crease (features, the default), whose nodes slide along it from the start. Every
// node of the top face stays on the deflected plane outside the deflected hole, every node of
// the circle on the deflected circle, every node of the hole's wall on the shifted cylinder; the
// mesh is valid and its wall's faces are off the deflected faces by the cylinder's faceting only.
TEST(DeformTrimmedFaces, APlateWithAHoleSlidesOnItsTrimmedTopFaceAndTheHolesWall) {
  const TrimmedPlate plate({.cone_deg = 0.0, .shift_x = 0.3, .shift_y = 0.1});
  const Hole& hole = plate.hole();
  const DeformRun r = plate.deform();
  ASSERT_EQ(r.result.exit_code, 0) << r.result.output;
  expect_on_trimmed_wall(hole, r, 0.15);  // 0.187 measured (0.196 undeformed)

  int top = 0, rim = 0, top_at_rim = 0;
  double closest = std::numeric_limits<double>::infinity(), rim_off = 0.0, hole_off = 0.0;
  for (const WallNode& n : r.wall) {
    const double radial = hole.radius(n.after);
    switch (n.start) {
      case Start::top:  // on the top face, outside the hole: none over its footprint
        ++top;
        closest = std::min(closest, radial);
        if (radial < kHole + 1e-9) ++top_at_rim;
        EXPECT_GE(radial, kHole - 1e-9) << n.before.x << ", " << n.before.y;
        break;
      case Start::rim:  // on the deflected circle: radius 2, the top face's height
        ++rim;
        rim_off = std::max({rim_off, std::abs(radial - kHole), std::abs(n.after.z - (kTop + bulge(kHole)))});
        break;
      case Start::hole:
        hole_off = std::max(hole_off, std::abs(radial - kHole));
        break;
    }
  }
  EXPECT_GT(top, 100);
  EXPECT_EQ(top_at_rim, 0);  // the circle's own nodes hold the rim
  EXPECT_GT(closest, kHole + 0.05) << "the top face's nodes nearest the deflected hole";  // 2.20 measured
  EXPECT_LT(rim_off, 1e-4);  // the bulge's fit at the circle (1e-5 measured)
  EXPECT_LT(hole_off, 1e-9);
  RecordProperty("top_face_nodes", top);
  RecordProperty("circle_nodes", rim);
  RecordProperty("closest_top_node_to_the_hole", fmt::format("{:.4f}", closest));

  // The circle is a crease of the wall, held by its own nodes; the faces are joined along it.
  const auto& features = r.report["features"];
  ASSERT_EQ(features.size(), 1u) << features.dump();
  EXPECT_EQ(features[0]["kind"], "crease");
  EXPECT_EQ(features[0]["faces"], nlohmann::json(plate.wall_faces()));
  EXPECT_NEAR(features[0]["angle_deg"].get<double>(), 90.0, 1.0);
  EXPECT_EQ(features[0]["nodes"].size(), static_cast<std::size_t>(rim));
  EXPECT_LT(features[0]["distance"].get<double>(), 1e-9);
  const auto& deflections = r.report["deflections"][0];
  EXPECT_EQ(deflections["wall"], "faces");
  EXPECT_EQ(deflections["shared_edges"], 1);
  EXPECT_LT(deflections["max_edge_gap"].get<double>(), 1e-8);

  // The wall's faces against the deflected faces: the cylinder's faceting, a chord's sagitta
  // h^2 / 8R with R = 2 and h up to 0.6 (0.0245 measured); the other side below
  // (TheWallDistanceLeavesOutTheHolesFootprint).
  ASSERT_EQ(r.report["wall_deviations"].size(), 1u);
  const auto& wall = r.report["wall_deviations"][0];
  EXPECT_EQ(wall["shape"], "faces");
  EXPECT_LT(wall["mesh_to_shape"]["distance"].get<double>(), 0.03);
}

// A countersunk hole: a cone at 20 degrees to the plate below the circle, the wall shifted by
// (0.9, 0.3). The wall turns by 20 degrees at the circle, no crease: nodes slide across it. As
// the hole moves by the shift the wall's nodes lag behind it (the ceiling is fixed), so on the
// side the hole moves to the circle overtakes the nodes that were on it and the top face's
// nodes next to it: the deflected top face ends short of them. Each must go onto the cone, not
// stay on the plane's continuation over the hole (up to 0.14 above the cone there): that is
// the trimming's work, the top face's projection outside its loops moved onto its binding
// circle, where the cone is nearer. With the trimming taken out this test fails.
TEST(DeformTrimmedFaces, NodesTheHoleOvertakesGoOntoItsWallNotOverItsFootprint) {
  const TrimmedPlate plate({.cone_deg = 20.0, .shift_x = 0.9, .shift_y = 0.3});
  const Hole& hole = plate.hole();
  // From the paper's start. With the predictor (the default) the run succeeds too, every node
  // on the faces as hotmesh fits them, but 3 of the 402 wall nodes end 0.6e-3 to 2e-3 from the
  // exact deflected cone, beyond this test's 5e-4: nodes the hole overtakes start on the cone
  // elsewhere and come to rest elsewhere. Not yet understood (issue 25's note).
  const DeformRun r = plate.deform("", "{predictor: false}");
  ASSERT_EQ(r.result.exit_code, 0) << r.result.output;
  expect_on_trimmed_wall(hole, r, 0.1);  // 0.154 measured

  int from_circle = 0, from_top = 0;
  for (const WallNode& n : r.wall) {
    if (n.start == Start::hole || hole.radius(n.after) >= kHole - 1e-3) continue;
    ++(n.start == Start::rim ? from_circle : from_top);
  }
  // 20 and 8 measured: the test needs nodes of both kinds carried over the footprint.
  EXPECT_GE(from_circle, 10);
  EXPECT_GE(from_top, 3);
  RecordProperty("circle_nodes_now_on_the_cone", from_circle);
  RecordProperty("top_face_nodes_now_on_the_cone", from_top);
}

// ---------------------------------------------------------------------------------------------
// Bugs found with these cases: the first two mended, the last kept as a disabled test until it is.

// The cylindrical hole with `features: off`: the circle is no crease, and nothing holds its
// nodes on it but the trimming. A node the projection puts on the circle (the top face's
// projection moved onto its binding loop) is held by the direction to it, the distance's
// gradient there; with the plane's normal it slid on into the hole at every Newton step and was
// put back, and the first increment stalled (exit 1). Without the trimming the run ended with 23
// of the circle's 42 nodes over the hole's footprint, up to 0.074 inside the circle.
TEST(DeformTrimmedFaces, ACylindricalHoleWithoutFeaturesKeepsItsNodesOnTheTrimmedWall) {
  const TrimmedPlate plate({.cone_deg = 0.0, .shift_x = 0.3, .shift_y = 0.1});
  const DeformRun r = plate.deform(", features: off");
  ASSERT_EQ(r.result.exit_code, 0) << r.result.output;
  expect_on_trimmed_wall(plate.hole(), r, 0.1);
}

// report.json's wall_deviations against the deflected faces: the top face's samples over the
// hole's footprint are beyond its trimming loop, no points of it, and left out. (Before, the
// face was measured over its whole rectangle: shape_to_mesh 1.99 mm at the deflected hole's
// centre for a mesh whose nodes are all on the wall, and `hotmesh check --case` the same.)
TEST(DeformTrimmedFaces, TheWallDistanceLeavesOutTheHolesFootprint) {
  const TrimmedPlate plate({.cone_deg = 0.0, .shift_x = 0.3, .shift_y = 0.1});
  const DeformRun r = plate.deform();
  ASSERT_EQ(r.result.exit_code, 0) << r.result.output;
  EXPECT_LT(r.report["wall_deviations"][0]["shape_to_mesh"]["distance"].get<double>(), 0.03);
  EXPECT_LT(r.report["wall_deviations"][0]["hausdorff"].get<double>(), 0.03);
}

// The corner pass on the cylindrical hole, whose crease holds every node of the circle from the
// start (features: largest_offset 0, nothing to give): it starts at rest, is accepted at once
// and keeps the motion's mesh and quality, every circle node still on the crease. (It failed at
// every halving before, the residual 0.996 of the initial one after 30 Newton iterations, and
// the run noted "the corners of the sliding walls could not be given nodes": the circle node
// the motion had slid just past the cylinder's seam was no longer found on the crease, since
// the projection onto the cylinder's top side stopped at the seam, and was given the crease as
// a corner line that pulled it 0.033 back to the seam while its constraints left it free along
// the crease; and, that mended, the projector left points moved along the wall by less than its
// tolerance where its search started, 1e-11 from where the solver put them, a residual twice
// what rounding leaves.)
TEST(DeformTrimmedFaces, TheCornerPassLeavesAHoleWhoseCreaseHasItsNodesAlone) {
  const TrimmedPlate plate({.cone_deg = 0.0, .shift_x = 0.3, .shift_y = 0.1});
  const DeformRun r = plate.deform();
  ASSERT_EQ(r.result.exit_code, 0) << r.result.output;
  EXPECT_THAT(r.result.output, ::testing::Not(HasSubstr("could not be given nodes")));
  expect_on_trimmed_wall(plate.hole(), r, 0.18);  // 0.187, the motion's
  int passes = 0;
  for (const auto& increment : r.report["increments"]) {
    if (!increment.value("corner_pass", false)) continue;
    ++passes;
    EXPECT_TRUE(increment["accepted"].get<bool>()) << increment.dump();
    EXPECT_LE(increment["newton_iterations"].get<int>(), 1) << increment.dump();
  }
  EXPECT_GT(passes, 0);
  const auto& features = r.report["features"];
  ASSERT_EQ(features.size(), 1u) << features.dump();
  EXPECT_EQ(features[0]["nodes"].size(), 42u);
  EXPECT_EQ(features[0]["largest_offset"].get<double>(), 0.0);
  EXPECT_LT(features[0]["distance"].get<double>(), 1e-9);
}

}  // namespace
}  // namespace hotmesh::app
