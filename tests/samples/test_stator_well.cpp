// Tests of the stator_well sample (samples/stator_well): the small sector is a valid hex mesh
// with good cells, the expected patches, periodic faces that match by rotation and wall nodes
// on the CAD curves; the FEM tables parse, lie on their walls, agree at shared corners and
// describe the severe case; the sizes are counted without building them; the case files pass
// hotmesh's own set-up (tables on the CAD faces named).
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>

#include <nlohmann/json.hpp>

#include "dimensions.hpp"
#include "fem_tables.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/validate.hpp"
#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/geometry/curve_projector.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/case_file.hpp"
#include "hotmesh/setup/case_setup.hpp"
#include "hotmesh/io/deflection_csv.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "stator_well.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::samples::stator_well {
namespace {

const geometry::Axis kZ({0, 0, 0}, {0, 0, 1});

/// The small sector, its CAD file and tables written to a temporary folder, built once.
struct Small {
  std::vector<ProfileCurve> loop = profile();
  BlockMesher mesher{block_layout(loop), spacing_field()};
  Size size = size_for_cells(mesher, kSmallCells);
  QuadMesh section = mesher.mesh(size.refinement);
  mesh::Mesh mesh = sector_mesh(section, loop, size.theta_cells);
  SevereCase severe;
  std::vector<FemTable> tables = fem_tables(loop, severe);
  hotmesh::test::TempDir dir;
  std::optional<geometry::CadModel> cad;

  Small() {
    io::write_file_atomically(dir / kCadFile, geometry::to_step(cad_model(loop)));
    cad = geometry::CadModel::read(dir / kCadFile);
  }
  /// The meridional curve of one CAD face about z.
  geometry::CurveProjector face_curve(int id) const {
    const int ids[] = {id};
    return geometry::CurveProjector(geometry::DeflectedCurve(cad->meridional_curve(ids, {.axis = kZ}).curve));
  }
  const FemTable& table(Patch p) const {
    return *std::find_if(tables.begin(), tables.end(), [&](const FemTable& t) { return t.patch == p; });
  }
};

const Small& small() {
  static const Small s;
  return s;
}

geometry::Vec2 rz(const geometry::Vec3& p) { return {std::hypot(p.x, p.y), p.z}; }

TEST(StatorWellSizes, TheSmallSizeIsAbout20kCellsCountedWithoutBuildingIt) {
  const Small& s = small();
  EXPECT_NEAR(static_cast<double>(s.size.cells), static_cast<double>(kSmallCells), 0.03 * kSmallCells);
  EXPECT_GE(s.size.cells, 15000);
  EXPECT_LE(s.size.cells, 25000);
  EXPECT_GE(s.size.theta_cells, 3);
  EXPECT_EQ(static_cast<std::int64_t>(s.section.quads.size()), s.size.quads);
  EXPECT_EQ(static_cast<std::int64_t>(s.mesh.cell_count()), s.size.cells);
  EXPECT_EQ(static_cast<std::int64_t>(s.mesh.node_count()), s.size.nodes);
}

TEST(StatorWellSizes, OneParameterReachesThePapersSize) {
  const Small& s = small();
  const Size medium = size_for_cells(s.mesher, 200000);
  const Size paper = size_for_cells(s.mesher, 2700000);
  EXPECT_NEAR(static_cast<double>(medium.cells), 2e5, 0.02 * 2e5);
  EXPECT_NEAR(static_cast<double>(paper.cells), 2.7e6, 0.02 * 2.7e6);
  EXPECT_GT(medium.refinement, s.size.refinement);
  EXPECT_GT(paper.theta_cells, medium.theta_cells);
  EXPECT_GT(paper.quads, 4 * s.size.quads);
  // Every count grows with the refinement: the size is one monotone parameter.
  std::int64_t previous = 0;
  for (double r = 0.5; r < 4.5; r += 0.25) {
    const Size z = size_at(s.mesher, r);
    EXPECT_GE(z.cells, previous) << r;
    previous = z.cells;
  }
}

TEST(StatorWellMesh, IsValidWithPositiveCornersAndGoodCells) {
  const Small& s = small();
  mesh::Mesh copy = s.mesh;
  const auto report = mesh::validate_mesh(copy);
  EXPECT_EQ(report.reoriented_cells, 0u);  // written with positive corner Jacobians
  EXPECT_EQ(report.interior_patch_faces, 0u);
  const auto quality = mesh::summarize_quality(mesh::scaled_jacobians(s.mesh.cells, s.mesh.points));
  EXPECT_EQ(quality.inverted_cells, 0u);
  EXPECT_GT(quality.min_scaled_jacobian, 0.7);  // the 135-degree corners where fillet blocks meet
  EXPECT_GT(quality.mean_scaled_jacobian, 0.98);
}

TEST(StatorWellMesh, PatchesAreNamedAndTaggedInOrderAndCoverTheBoundary) {
  const Small& s = small();
  const char* expected[] = {"inlet",  "outlet",        "casing", "blade",         "stator_outer", "stator_front",
                            "fins",   "stator_rear",   "rim_up", "disc_up_upper", "joint",        "disc_up_lower",
                            "disc_base", "disc_down", "rim_down", "per_lo",       "per_hi"};
  ASSERT_EQ(s.mesh.patches.size(), std::size(expected));
  std::size_t faces = 0;
  for (std::size_t i = 0; i < s.mesh.patches.size(); ++i) {
    EXPECT_EQ(s.mesh.patches[i].name, expected[i]);
    EXPECT_EQ(s.mesh.patches[i].tag, static_cast<int>(i) + 1);
    EXPECT_FALSE(s.mesh.patches[i].faces.empty()) << expected[i];
    faces += s.mesh.patches[i].faces.size();
  }
  mesh::Mesh copy = s.mesh;
  EXPECT_EQ(mesh::validate_mesh(copy).boundary_faces, faces);  // every boundary face in one patch
}

TEST(StatorWellMesh, PeriodicFacesMatchByTheSectorRotation) {
  const Small& s = small();
  const auto& lo = s.mesh.find_patch("per_lo")->nodes;
  const auto& hi = s.mesh.find_patch("per_hi")->nodes;
  ASSERT_EQ(lo.size(), hi.size());
  const double a = kSectorDegrees * std::numbers::pi / 180.0;
  // Sorted by (z, r), rotated per_lo nodes and per_hi nodes pair up one to one.
  const auto key = [](const geometry::Vec3& p) { return std::pair{p.z, std::hypot(p.x, p.y)}; };
  std::vector<geometry::Vec3> rotated, target;
  for (auto n : lo) {
    const auto& p = s.mesh.points[static_cast<std::size_t>(n)];
    EXPECT_NEAR(p.y, 0.0, 1e-15);  // theta = 0
    rotated.push_back({p.x * std::cos(a) - p.y * std::sin(a), p.x * std::sin(a) + p.y * std::cos(a), p.z});
  }
  for (auto n : hi) target.push_back(s.mesh.points[static_cast<std::size_t>(n)]);
  const auto by_key = [&](const geometry::Vec3& p, const geometry::Vec3& q) { return key(p) < key(q); };
  std::sort(rotated.begin(), rotated.end(), by_key);
  std::sort(target.begin(), target.end(), by_key);
  double worst = 0.0;
  for (std::size_t i = 0; i < rotated.size(); ++i) worst = std::max(worst, distance(rotated[i], target[i]));
  EXPECT_LT(worst, 1e-12);
}

TEST(StatorWellMesh, WallNodesLieOnTheCadCurvesOfTheirPatch) {
  const Small& s = small();
  for (int p = 0; p < static_cast<int>(Patch::per_lo); ++p) {
    const auto patch = static_cast<Patch>(p);
    std::vector<geometry::CurveProjector> curves;
    for (int id : cad_faces(s.loop, patch)) curves.push_back(s.face_curve(id));
    ASSERT_FALSE(curves.empty()) << name(patch);
    double worst = 0.0;
    for (auto n : s.mesh.find_patch(name(patch))->nodes) {
      const auto q = rz(s.mesh.points[static_cast<std::size_t>(n)]);
      double d = std::numeric_limits<double>::infinity();
      for (const auto& c : curves) d = std::min(d, c.project(q, 0.0).distance);
      worst = std::max(worst, d);
    }
    EXPECT_LT(worst, 1e-10) << name(patch);
  }
}

TEST(StatorWellCad, FacesAreSurfacesOfRevolutionAboutTheEngineAxis) {
  const Small& s = small();
  ASSERT_EQ(s.cad->faces().size(), s.loop.size());
  const auto order = cad_face_order(s.loop);
  for (const auto& face : s.cad->faces()) {
    const ProfileCurve& c = s.loop[static_cast<std::size_t>(order[static_cast<std::size_t>(face.id - 1)])];
    EXPECT_EQ(face.name, c.name);
    const auto curved = c.curve.degree() > 1 ? geometry::SurfaceKind::revolution : face.kind;
    EXPECT_EQ(face.kind, curved) << c.name;
    if (face.kind != geometry::SurfaceKind::plane) {
      ASSERT_TRUE(face.axis) << c.name;
      EXPECT_LT(norm(cross(face.axis->direction(), kZ.direction())), 1e-12) << c.name;
      EXPECT_LT(std::hypot(face.axis->origin().x, face.axis->origin().y), 1e-12) << c.name;
    }
  }
}

TEST(StatorWellTables, ParseAndLieOnTheirWallsWithUniqueIds) {
  const Small& s = small();
  ASSERT_EQ(s.tables.size(), 10u);
  for (const FemTable& t : s.tables) {
    const auto parsed = io::parse_deflection_csv(table_csv(t, s.severe), table_file(t.patch));
    ASSERT_EQ(parsed.frame, geometry::SampleFrame::meridional) << name(t.patch);
    ASSERT_EQ(parsed.size(), t.nodes.size());
    EXPECT_EQ(std::set<std::int64_t>(parsed.ids.begin(), parsed.ids.end()).size(), parsed.size()) << name(t.patch);
    const auto faces = cad_faces(s.loop, t.patch);
    const geometry::CurveProjector wall(geometry::DeflectedCurve(s.cad->meridional_curve(faces, {.axis = kZ}).curve));
    for (std::size_t j = 0; j < parsed.size(); ++j) {
      const geometry::Vec2 q{parsed.points[j].x, parsed.points[j].y};
      EXPECT_LT(wall.project(q, 0.0).distance, 1e-9) << name(t.patch) << " node " << parsed.ids[j];
    }
  }
}

TEST(StatorWellTables, ACornerSharedByTwoTablesHasOneIdAndMovesAlikeInBoth) {
  const Small& s = small();
  std::map<std::int64_t, std::vector<FemNode>> by_id;
  for (const FemTable& t : s.tables) {
    for (const FemNode& n : t.nodes) by_id[n.id].push_back(n);
  }
  int shared = 0;
  for (const auto& [id, nodes] : by_id) {
    if (nodes.size() < 2) continue;
    ++shared;
    for (const FemNode& n : nodes) {
      EXPECT_EQ(distance(n.zr, nodes.front().zr), 0.0) << id;
      EXPECT_EQ(distance(n.dzr, nodes.front().dzr), 0.0) << id;
    }
  }
  // Rotor: rim_up/disc_up_upper, disc_up_upper/joint, joint/disc_up_lower,
  // disc_up_lower/disc_base, disc_base/disc_down, disc_down/rim_down; stator: stator_front/fins,
  // fins/stator_rear.
  EXPECT_EQ(shared, 8);
}

TEST(StatorWellTables, DescribeTheSevereCase) {
  const Small& s = small();
  using namespace dims;
  // The rotor moves axially; the stator does not.
  const auto stator = [](Patch p) { return p == Patch::stator_front || p == Patch::fins || p == Patch::stator_rear; };
  for (const FemTable& t : s.tables) {
    for (const FemNode& n : t.nodes) EXPECT_EQ(n.dzr.x, stator(t.patch) ? 0.0 : s.severe.axial_shift) << name(t.patch);
  }
  // The seal clearance between the fin tips and the disc base closes by about 60 %.
  double tip = std::numeric_limits<double>::quiet_NaN(), base = tip;
  for (const FemNode& n : s.table(Patch::fins).nodes) {
    if (std::abs(n.zr.y - kRFinTip * 1e-3) < 1e-12) tip = n.dzr.y;
  }
  for (const FemNode& n : s.table(Patch::disc_base).nodes) {
    if (n.zr.x > kZStatorFront * 1e-3 && n.zr.x < kZStatorRear * 1e-3) base = n.dzr.y;
  }
  const double closure = (base - tip) / (kClearance * 1e-3);
  EXPECT_GT(closure, 0.55);
  EXPECT_LT(closure, 0.65);
  // At the joint's end the deflection jumps by the joint's jump between two points 1 mm apart.
  const auto& joint = s.table(Patch::joint).nodes;
  const auto b = std::find_if(joint.begin(), joint.end(), [](const FemNode& n) {
    return distance(n.zr, dims::at(kZJointEnd, kRJoint + kJointGap)) < 1e-12;
  });
  const auto c = std::find_if(joint.begin(), joint.end(), [](const FemNode& n) { return distance(n.zr, dims::at(kZJointEnd, kRJoint)) < 1e-12; });
  ASSERT_NE(b, joint.end());
  ASSERT_NE(c, joint.end());
  EXPECT_NEAR(distance(b->zr, c->zr), kJointGap * 1e-3, 1e-15);
  EXPECT_NEAR(c->dzr.y - b->dzr.y, s.severe.joint_jump - s.severe.rotor_growth * kJointGap / kRHub, 1e-12);
}

TEST(StatorWellTables, FemNodesAreCoarserThanTheCfdWallsAndNotOnTheirNodes) {
  const Small& s = small();
  for (const FemTable& t : s.tables) {
    // The CFD wall nodes of the patch in the periodic plane theta = 0.
    std::vector<geometry::Vec2> cfd;
    for (auto n : s.mesh.find_patch(name(t.patch))->nodes) {
      const auto& p = s.mesh.points[static_cast<std::size_t>(n)];
      if (p.y == 0.0) cfd.push_back({p.z, p.x});
    }
    EXPECT_LT(t.nodes.size(), cfd.size()) << name(t.patch);
    for (std::size_t j = 1; j < t.nodes.size(); ++j) {
      EXPECT_LE(distance(t.nodes[j].zr, t.nodes[j - 1].zr), s.severe.fem_spacing * (1.0 + 1e-9)) << name(t.patch);
    }
    // Away from the profile's corners (where both models need a node), no FEM node sits on a
    // CFD node.
    int coincident = 0;
    for (const FemNode& f : t.nodes) {
      bool corner = false;
      for (const ProfileCurve& c : s.loop) {
        corner = corner || distance(f.zr, c.curve.point(c.curve.first_parameter())) < 1e-12;
      }
      if (corner) continue;
      for (const auto& q : cfd) {
        if (distance(f.zr, q) < 1e-9) {
          ++coincident;
          ADD_FAILURE() << name(t.patch) << ": FEM node " << f.id << " at (" << f.zr.x << ", " << f.zr.y << ") is a CFD node";
        }
      }
    }
    EXPECT_EQ(coincident, 0) << name(t.patch);
  }
}

TEST(StatorWellCases, BothCaseFilesPassTheSetUpOfHotmeshDeform) {
  const Small& s = small();
  io::write_gmsh(s.dir / kMeshFile, s.mesh, {.binary = true});
  for (const FemTable& t : s.tables) io::write_file_atomically(s.dir / table_file(t.patch), table_csv(t, s.severe));
  for (const bool sliding : {true, false}) {
    io::write_file_atomically(s.dir / case_file_name("test", sliding), case_file(s.loop, "test", sliding));
    const io::Case c = io::read_case(s.dir / case_file_name("test", sliding));
    io::check_case_against_mesh(c, s.mesh);
    int sliders = 0, periodic = 0, passive = 0;
    for (const auto& p : c.patches) {
      sliders += p.role == io::PatchRole::sliding ? 1 : 0;
      passive += p.role == io::PatchRole::passive ? 1 : 0;
      if (p.role == io::PatchRole::periodic) {
        ++periodic;
        if (p.name == "per_lo") {
          EXPECT_EQ(p.partner, "per_hi");
          EXPECT_DOUBLE_EQ(p.angle_deg, kSectorDegrees);
        }
      }
    }
    EXPECT_EQ(sliders, sliding ? 4 : 0);
    EXPECT_EQ(periodic, 2);
    EXPECT_EQ(passive, 3);
    // Every table is rebuilt on the CAD faces it names (nodes farther than the tolerance from
    // the faces would throw).
    const setup::CaseSetup setup = setup::set_up_case(c, s.mesh);
    EXPECT_EQ(setup.shapes.size(), 10u);
    for (const auto& shape : setup.shapes) EXPECT_LT(shape.reconstruction.max_node_distance_to_cad, 1e-9) << shape.patch;
  }
}

}  // namespace
}  // namespace hotmesh::samples::stator_well

namespace hotmesh::samples::stator_well {
namespace {

/// The whole pipeline on a sector of about 5 000 cells: the generator writes the CAD file,
/// mesh and tables, `hotmesh deform` runs the sample's case with sliding on (16 increments).
TEST(StatorWellRun, SlidingCaseEndsValidPeriodicAndOnTheDeflectedWalls) {
  test::TempDir dir;
  const auto generate = test::run_command(std::string(HOTMESH_MAKE_STATOR_WELL) + " --cells 5000 " +
                                          test::shell_quote(dir.path().string()));
  ASSERT_EQ(generate.exit_code, 0) << generate.output;
  ASSERT_TRUE(std::filesystem::exists(dir / "case_small.yaml"));  // the generator writes the case files too
  const auto run = test::run_command(std::string(HOTMESH_EXE) + " -q deform " +
                                     test::shell_quote((dir / "case_small.yaml").string()));
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto report = nlohmann::json::parse(test::read_text(dir / "case_small-out" / "report.json"));
  EXPECT_EQ(report["status"], "success");
  EXPECT_EQ(report["inverted_cells"], 0);
  EXPECT_GT(report["min_scaled_jacobian"].get<double>(), 0.5);
  EXPECT_GT(report["sliding_nodes"].get<int>(), 100);
  EXPECT_GT(report["passive_nodes"].get<int>(), 50);
  EXPECT_GT(report["periodic_pairs"].get<int>(), 1000);
  EXPECT_LT(report["max_periodic_mismatch_relative"].get<double>(), 1e-9);
  // After the last Newton step the sliding nodes moved back onto the deflected CAD walls by
  // next to nothing: they lie on them.
  EXPECT_LT(report["final_projection_distance_relative"].get<double>(), 1e-9);
  EXPECT_LT(report["max_normal_slip"].get<double>(), 1e-12);
  // Independently, `hotmesh check`: every node of the sliding walls lies on its deflected CAD
  // wall (faces of stator_well.step, tables as the case uses them) to 1e-6 of the mesh size,
  // first with the faces and tables given as options.
  std::string check = std::string(HOTMESH_EXE) + " -q check --form displacement --axis 0,0,0,0,0,1 --cad " +
                      test::shell_quote((dir / "stator_well.step").string()) + " --mesh " +
                      test::shell_quote((dir / "case_small-out" / "deformed.msh").string());
  for (const auto& [patch, faces] : {std::pair{"disc_up_upper", "32,33,34"}, std::pair{"disc_up_lower", "38"},
                                     std::pair{"disc_base", "39"}, std::pair{"disc_down", "40,41,42"}}) {
    check += fmt::format(" --map {}={} --deflection {}={}", patch, faces, patch,
                         test::shell_quote((dir / (std::string(patch) + ".csv")).string()));
  }
  const auto on_walls = test::run_command(check);
  EXPECT_EQ(on_walls.exit_code, 0) << on_walls.output;
  EXPECT_THAT(on_walls.output, ::testing::HasSubstr("4 of 4 patches within the tolerance"));
  // The same from the case file, as an engineer in a coupled loop runs it: every wall that
  // follows a table (prescribed or sliding) on its deflected CAD wall.
  const auto from_case = test::run_command(std::string(HOTMESH_EXE) + " -q check " +
                                           test::shell_quote((dir / "case_small-out" / "deformed.msh").string()) +
                                           " --case " + test::shell_quote((dir / "case_small.yaml").string()));
  EXPECT_EQ(from_case.exit_code, 0) << from_case.output;
  EXPECT_THAT(from_case.output, ::testing::HasSubstr("10 of 10 patches within the tolerance"));
  EXPECT_THAT(from_case.output, ::testing::HasSubstr("pass disc_down: "));
  EXPECT_THAT(from_case.output, ::testing::HasSubstr("against the deflected wall of the case (sliding): CAD faces 40, 41, 42"));
}

}  // namespace
}  // namespace hotmesh::samples::stator_well
