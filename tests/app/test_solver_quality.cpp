// Tests of the flow solver's measures (mesh/solver_quality.hpp) against OpenFOAM's own
// checkMesh -allGeometry on the same polyMesh folders (skipped without OpenFOAM): a wedge case
// (Debian's movingCone tutorial, by blockMesh), a skewed and graded 3D block by blockMesh, the
// hybrid box (tet, pyramid, prism, hex) by gmsh and gmshToFoam, and a mesh moved by hotmesh
// (the ramp channel, written back by `deform --foam-time`). hotmesh info and report.json give
// the maximum and average non-orthogonality, the maximum skewness, aspect ratio and volume
// ratio (checkMesh: its reciprocal, the minimum) that checkMesh prints, to 1 %. A
// snappyHexMesh mesh (a ball in a box, its split hexahedra OpenFOAM's polyhedra) is measured
// on its own cells, polyhedra on their faces, before and after hotmesh moves it; the moved
// mesh passes checkMesh.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "deform_cases.hpp"
#include "foam_fixtures.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "hybrid_meshes.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::app {
namespace {

using test::hotmesh;
using test::shell_quote;
namespace fs = std::filesystem;
namespace tf = test::foam;

#define SKIP_WITHOUT_OPENFOAM()            \
  if (tf::block_mesh_command().empty())    \
  GTEST_SKIP() << "OpenFOAM is not installed: " \
                  "run scripts/install-deps.sh (Debian's openfoam)"

/// The figures checkMesh -allGeometry prints.
struct CheckMeshFigures {
  double max_non_orthogonality = 0, mean_non_orthogonality = 0, max_skewness = 0, max_aspect_ratio = 0,
         min_volume_ratio = 0;
};

double figure(const std::string& output, const std::string& pattern) {
  std::smatch m;
  if (!std::regex_search(output, m, std::regex(pattern))) {
    ADD_FAILURE() << "checkMesh did not print /" << pattern << "/:\n" << output;
    return 0.0;
  }
  return std::stod(m[1].str());
}

/// checkMesh -allGeometry on the case `folder` (at `time` if given).
CheckMeshFigures check_mesh(const fs::path& folder, const std::string& time = "") {
  const auto r = test::run_command(tf::check_mesh_command() + " -allGeometry -case " + shell_quote(folder.string()) +
                                   (time.empty() ? "" : " -time " + time));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const std::string number = "([-+0-9.eE]+)";
  CheckMeshFigures k;
  k.max_non_orthogonality = figure(r.output, "Mesh non-orthogonality Max: " + number);
  k.mean_non_orthogonality = figure(r.output, "Mesh non-orthogonality Max: [-+0-9.eE]+ average: " + number);
  k.max_skewness = figure(r.output, "[Mm]ax skewness = " + number);
  k.max_aspect_ratio = figure(r.output, "[Mm]ax aspect ratio[ =:]+" + number);
  k.min_volume_ratio = figure(r.output, "Face volume ratio : minimum: " + number);
  return k;
}

/// report.json's or info's quality against checkMesh's figures, each to 1 %.
void expect_as_check_mesh(const nlohmann::json& quality, const CheckMeshFigures& k) {
  const auto near = [](double hotmesh, double openfoam, const char* what) {
    EXPECT_NEAR(hotmesh, openfoam, 0.01 * std::abs(openfoam) + 1e-6) << what;
  };
  near(quality["non_orthogonality"]["max"].get<double>(), k.max_non_orthogonality, "max non-orthogonality");
  near(quality["non_orthogonality"]["mean"].get<double>(), k.mean_non_orthogonality, "average non-orthogonality");
  near(quality["skewness"]["max"].get<double>(), k.max_skewness, "max skewness");
  near(quality["aspect_ratio"]["max"].get<double>(), k.max_aspect_ratio, "max aspect ratio");
  near(1.0 / quality["volume_ratio"]["max"].get<double>(), k.min_volume_ratio, "volume ratio");
}

nlohmann::json info_quality(const fs::path& mesh) {
  const auto r = hotmesh("info --json " + shell_quote(mesh.string()));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return nlohmann::json::parse(r.output)["quality"];
}

TEST(SolverQuality, MovingConeWedgeAsCheckMeshSeesIt) {
  SKIP_WITHOUT_OPENFOAM();
  const fs::path tutorial = "/usr/share/doc/openfoam-examples/examples/incompressible/pimpleFoam/laminar/movingCone";
  if (!fs::exists(tutorial)) GTEST_SKIP() << "openfoam-examples is not installed: run scripts/install-deps.sh";
  test::TempDir dir;
  const fs::path cone = dir / "movingCone";
  fs::copy(tutorial, cone, fs::copy_options::recursive);
  ASSERT_EQ(tf::run_block_mesh(cone).exit_code, 0);
  const nlohmann::json q = info_quality(cone);
  expect_as_check_mesh(q, check_mesh(cone));
  // The wedge's cells are measured as the wedge's prisms: its planes as slab would put the
  // cells' centres at their areas' centroids, not their volumes', and change the figures.
  EXPECT_GT(q["non_orthogonality"]["max"].get<double>(), 15.0);
  EXPECT_EQ(q["non_orthogonality"]["severe_faces"].get<int>(), 0);
  // The wedge's sides on its axis have no area and no angle.
  EXPECT_LT(q["non_orthogonality"]["max_boundary"].get<double>(), 30.0);
}

/// Debian's movingCone tutorial meshed by blockMesh in `dir`/cone, with a case moving the cone
/// 1.6 mm along the axis as OpenFOAM's own motion does at t = 0.0016 (a rigid translation of
/// the movingWall patch, the far fields and the axis slip, the rest fixed) and `material`.
fs::path moving_cone_case(const fs::path& dir, const std::string& material) {
  const fs::path tutorial = "/usr/share/doc/openfoam-examples/examples/incompressible/pimpleFoam/laminar/movingCone";
  const fs::path cone = dir / "cone";
  if (!fs::exists(cone)) {
    fs::copy(tutorial, cone, fs::copy_options::recursive);
    EXPECT_EQ(tf::run_block_mesh(cone).exit_code, 0);
    const io::LoadedMesh loaded = io::read_mesh(cone);
    std::string table = "x, y, dx, dy\n";
    for (const mesh::NodeId n : loaded.mesh.find_patch("movingWall")->nodes) {
      const auto& p = loaded.mesh.points[static_cast<std::size_t>(n)];
      table += fmt::format("{:.17g}, {:.17g}, 0.0016, 0\n", p.x, p.y);
    }
    test::write_text(dir / "cone.csv", table);
  }
  const fs::path yaml = dir / "cone.yaml";
  test::write_text(yaml, "mesh: cone\nmaterial: " + material +
                             "\npatches:\n  movingWall: {role: prescribed, deflection: {file: cone.csv, degree: 1}}\n"
                             "  farFieldMoving: {role: slip}\n  farField: {role: slip}\n  axis: {role: slip}\n"
                             "  fixedWall: {role: fixed}\n  left: {role: fixed}\n");
  return yaml;
}

TEST(SolverQuality, MovingConeStiffenedByDistanceToTheConeKeepsItsCellsOrthogonal) {
  SKIP_WITHOUT_OPENFOAM();
  if (!fs::exists("/usr/share/doc/openfoam-examples/examples/incompressible/pimpleFoam/laminar/movingCone")) {
    GTEST_SKIP() << "openfoam-examples is not installed: run scripts/install-deps.sh";
  }
  test::TempDir dir;
  // The paper's pseudo-material, and cells stiffened by their distance to the cone (docs/method.md).
  std::vector<CheckMeshFigures> figures;
  for (const std::string material : {"{}", "{law: uniform, drop_jacobian: false, wall_distance_exponent: 1.5}"}) {
    const fs::path yaml = moving_cone_case(dir.path(), material);
    const auto r = hotmesh("deform " + shell_quote(yaml.string()) + " -o " + shell_quote((dir / "out").string()) +
                           " --force --threads 1 --foam-time 0.0016");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    figures.push_back(check_mesh(dir / "cone", "0.0016"));
    fs::remove_all(dir / "cone" / "0.0016");
  }
  // OpenFOAM's own motion with the tutorial's settings (moveDynamicMesh): 20.1 degrees, 0.49.
  EXPECT_GT(figures[0].max_non_orthogonality, 70.0);
  EXPECT_GT(figures[0].max_skewness, 3.0);
  EXPECT_LT(figures[1].max_non_orthogonality, 45.0);
  EXPECT_LT(figures[1].max_skewness, 0.6);
}

TEST(SolverQuality, MovingConeWithTheQualityStepIsAheadOfOpenFoamsOwnMotion) {
  SKIP_WITHOUT_OPENFOAM();
  if (!fs::exists("/usr/share/doc/openfoam-examples/examples/incompressible/pimpleFoam/laminar/movingCone")) {
    GTEST_SKIP() << "openfoam-examples is not installed: run scripts/install-deps.sh";
  }
  test::TempDir dir;
  // Cells stiffened by their distance to the cone, and the quality step after each increment
  // (docs/method.md): checkMesh on the moved case.
  const fs::path yaml =
      moving_cone_case(dir.path(), "{law: uniform, drop_jacobian: false, wall_distance_exponent: 1.5}\n"
                                   "quality: {smoothing: on}");
  const auto r = hotmesh("deform " + shell_quote(yaml.string()) + " -o " + shell_quote((dir / "out").string()) +
                         " --force --threads 1 --foam-time 0.0016");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const CheckMeshFigures moved = check_mesh(dir / "cone", "0.0016");
  // OpenFOAM's own motion with the tutorial's settings (moveDynamicMesh): 20.1 degrees, 0.49;
  // the undeformed mesh: 19.0 degrees, 0.53.
  EXPECT_LT(moved.max_non_orthogonality, 19.0);
  EXPECT_LT(moved.max_skewness, 0.45);
  const nlohmann::json report = nlohmann::json::parse(test::read_text(dir / "out" / "report.json"));
  EXPECT_GT(report["quality"]["min_scaled_jacobian"].get<double>(), 0.8);
  std::size_t smoothed = 0;
  for (const auto& attempt : report["increments"]) smoothed += attempt["smoothed_nodes"].get<std::size_t>();
  EXPECT_GT(smoothed, 0u);
}

/// A hexahedral block by blockMesh whose vertices are moved off a box and whose cells are
/// graded in all three directions: non-orthogonal, skewed and stretched cells.
constexpr const char* kSkewedBlock = R"(
vertices ((0 0 0) (4 0.6 0) (4.5 3 0.4) (0.3 2.2 0) (0.2 0.1 1.4) (3.9 0.2 1.1) (4.8 3.4 2) (-0.4 2.5 1.2));
blocks (hex (0 1 2 3 4 5 6 7) (9 7 5) simpleGrading (6 0.2 3));
boundary (walls {type wall; faces ((0 4 7 3) (1 2 6 5) (0 1 5 4) (3 7 6 2) (0 3 2 1) (4 5 6 7));});
)";

TEST(SolverQuality, SkewedGradedHexBlockAsCheckMeshSeesIt) {
  SKIP_WITHOUT_OPENFOAM();
  test::TempDir dir;
  tf::write_block_mesh_case(dir / "block", kSkewedBlock);
  ASSERT_EQ(tf::run_block_mesh(dir / "block").exit_code, 0);
  const nlohmann::json q = info_quality(dir / "block");
  expect_as_check_mesh(q, check_mesh(dir / "block"));
  EXPECT_GT(q["non_orthogonality"]["max"].get<double>(), 20.0);
  EXPECT_GT(q["aspect_ratio"]["max"].get<double>(), 5.0);
  EXPECT_GT(q["volume_ratio"]["max"].get<double>(), 1.2);
}

TEST(SolverQuality, GmshHybridBoxAsCheckMeshSeesItPerCellType) {
  SKIP_WITHOUT_OPENFOAM();
  if (tf::gmsh_to_foam_command().empty()) GTEST_SKIP() << "gmshToFoam is not installed";
  test::TempDir dir;
  const auto msh = test::hybrid_msh("hybrid_box", 3, dir.path(), "msh22");
  tf::write_block_mesh_case(dir / "case", "");
  const auto r = test::run_command(tf::gmsh_to_foam_command() + " " + shell_quote(msh.string()) + " -case " +
                                   shell_quote((dir / "case").string()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json q = info_quality(dir / "case");
  expect_as_check_mesh(q, check_mesh(dir / "case"));
  // Every cell type has its own figures, and the worst of them is the mesh's.
  ASSERT_EQ(q["by_type"].size(), 4u);
  double worst_skewness = 0.0;
  for (const auto& [type, t] : q["by_type"].items()) {
    EXPECT_GT(t["skewness"]["max"].get<double>(), 0.0) << type;
    worst_skewness = std::max(worst_skewness, t["skewness"]["max"].get<double>());
  }
  EXPECT_DOUBLE_EQ(worst_skewness, q["skewness"]["max"].get<double>());
}


TEST(SolverQuality, MeshMovedByHotmeshAsCheckMeshSeesIt) {
  SKIP_WITHOUT_OPENFOAM();
  test::TempDir dir;
  const fs::path cfd = dir / "cfd";
  tf::write_block_mesh_case(cfd, tf::kRampChannel);
  ASSERT_EQ(tf::run_block_mesh(cfd).exit_code, 0);
  fs::copy_file(test::kSample / "ramp.csv", dir / "ramp.csv");
  test::write_text(dir / "foam.yaml",
                   "mesh: cfd\nsolver: {increments: 8}\npatches:\n  left: {role: fixed}\n  right: {role: slip}\n"
                   "  top: {role: sliding}\n  bottom: {role: sliding, deflection: {file: ramp.csv, degree: 1}}\n");
  const auto out = dir / "out";
  const auto r = hotmesh("deform " + shell_quote((dir / "foam.yaml").string()) + " -o " + shell_quote(out.string()) +
                         " --threads 1 --foam-time 1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("max non-orthogonality"), std::string::npos) << r.output;
  const nlohmann::json report = nlohmann::json::parse(test::read_text(out / "report.json"));
  const nlohmann::json& moved = report["quality"];
  expect_as_check_mesh(moved, check_mesh(cfd, "1"));
  // The motion made the cells less orthogonal than blockMesh's rectangles (0 degrees).
  EXPECT_GT(moved["non_orthogonality"]["max"].get<double>(), 1.0);
  EXPECT_NEAR(report["mesh"]["quality"]["non_orthogonality"]["max"].get<double>(), 0.0, 1e-6);
}

/// checkMesh's count of polyhedra ("polyhedra:     248") in its output `r`, which says Mesh OK.
std::size_t check_mesh_polyhedra(const test::CommandResult& r) {
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("Mesh OK."), std::string::npos) << r.output;
  return static_cast<std::size_t>(figure(r.output, "polyhedra: +([0-9]+)"));
}

#define SKIP_WITHOUT_SNAPPY()                         \
  if (tf::snappy_hex_mesh_command().empty())          \
  GTEST_SKIP() << "snappyHexMesh is not installed: " \
                  "run scripts/install-deps.sh (Debian's openfoam)"

TEST(SolverQuality, SnappyHexMeshPolyhedraAreMeasuredOnTheirOwnFacesAsCheckMeshDoes) {
  SKIP_WITHOUT_SNAPPY();
  test::TempDir dir;
  const fs::path cfd = dir / "ball";
  const auto made = tf::run_ball_in_box(cfd);
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const io::LoadedMesh loaded = io::read_mesh(cfd);
  const mesh::Polyhedra& poly = loaded.mesh.polyhedra;
  EXPECT_GT(poly.cells.size(), 100u);
  // checkMesh's polyhedra, and the snapped hexahedra with a concave corner.
  EXPECT_GE(poly.cells.size(),
            check_mesh_polyhedra(test::run_command(tf::check_mesh_command() + " -case " + shell_quote(cfd.string()))));
  // Every cell of the file stands first in the mesh's cells, the pieces follow.
  EXPECT_EQ(poly.file_points, tf::ascii_points(cfd / "constant" / "polyMesh" / "points").size());
  EXPECT_GT(loaded.mesh.node_count(), poly.file_points + poly.cells.size());
  EXPECT_EQ(loaded.mesh.cell_count(), poly.file_cells + poly.piece_of.size());
  EXPECT_EQ(loaded.validation.reoriented_cells, 0u);
  const nlohmann::json q = info_quality(cfd);
  expect_as_check_mesh(q, check_mesh(cfd));
  // The pieces' faces inside a polyhedron would give angles well above checkMesh's.
  EXPECT_LT(q["non_orthogonality"]["max"].get<double>(), 50.0);
}

TEST(SolverQuality, SnappyHexMeshFlangeTutorialIsReadWithItsPolyhedraAsCheckMeshSeesIt) {
  SKIP_WITHOUT_SNAPPY();
  const fs::path tutorial = "/usr/share/doc/openfoam-examples/examples/mesh/snappyHexMesh/flange";
  const fs::path surface = "/usr/share/doc/openfoam-examples/examples/resources/geometry/flange.stl.gz";
  if (!fs::exists(tutorial) || !fs::exists(surface)) GTEST_SKIP() << "openfoam-examples is not installed";
  // The tutorial's Allrun (about 10 s): blockMesh, surfaceFeatureExtract, snappyHexMesh.
  test::TempDir dir;
  const fs::path flange = dir / "flange";
  fs::copy(tutorial, flange, fs::copy_options::recursive);
  fs::copy_file(surface, flange / "constant" / "triSurface" / "flange.stl.gz");
  const auto gunzip = test::run_command("gunzip -f " + shell_quote((flange / "system" / "snappyHexMeshDict.gz").string()));
  ASSERT_EQ(gunzip.exit_code, 0) << gunzip.output;
  ASSERT_EQ(tf::run_block_mesh(flange).exit_code, 0);
  const std::string env = std::getenv("WM_PROJECT_DIR") ? "" : "WM_PROJECT_DIR=/usr/share/openfoam ";
  for (const std::string tool : {"surfaceFeatureExtract", "snappyHexMesh -overwrite"}) {
    const auto r = test::run_command(env + tool + " -case " + shell_quote(flange.string()));
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  const io::LoadedMesh loaded = io::read_mesh(flange);
  // hotmesh used to refuse it: "cell 25 has 12 faces (a polyhedron ...)".
  EXPECT_GE(loaded.mesh.polyhedra.cells.size(),
            check_mesh_polyhedra(test::run_command(tf::check_mesh_command() + " -case " + shell_quote(flange.string()))));
  EXPECT_GT(loaded.mesh.polyhedra.cells.size(), 1000u);
  expect_as_check_mesh(info_quality(flange), check_mesh(flange));
}

TEST(SolverQuality, SnappyHexMeshMovedByHotmeshWritesItsOwnPointsOnlyAndPassesCheckMesh) {
  SKIP_WITHOUT_SNAPPY();
  test::TempDir dir;
  const fs::path cfd = dir / "ball";
  const auto made = tf::run_ball_in_box(cfd);
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const io::LoadedMesh loaded = io::read_mesh(cfd);
  // The ball moves by (0.06, 0.03, -0.02) as a rigid body, the box stays.
  const geometry::Vec3 shift{0.06, 0.03, -0.02};
  std::string table = "x, y, z, dx, dy, dz\n";
  const auto& ball = loaded.mesh.find_patch("ball")->nodes;
  std::vector<bool> on_ball(loaded.mesh.polyhedra.file_points, false);
  for (const mesh::NodeId n : ball) {
    const auto i = static_cast<std::size_t>(n);
    if (i >= on_ball.size()) continue;  // a face centre hotmesh added
    on_ball[i] = true;
    const auto& p = loaded.mesh.points[i];
    table += fmt::format("{:.17g}, {:.17g}, {:.17g}, {}, {}, {}\n", p.x, p.y, p.z, shift.x, shift.y, shift.z);
  }
  test::write_text(dir / "ball.csv", table);
  // A closed wall without CAD folds over any plane: its table is interpolated smoothly (degree
  // 2), linear interpolation over a triangulation needs a wall that does not fold.
  test::write_text(dir / "ball.yaml", "mesh: ball\nsolver: {increments: 2}\npatches:\n"
                                      "  ball: {role: prescribed, deflection: {file: ball.csv, mode: surface, degree: 2}}\n"
                                      "  box: {role: fixed}\n");
  const auto out = dir / "out";
  const auto r = hotmesh("deform " + shell_quote((dir / "ball.yaml").string()) + " -o " + shell_quote(out.string()) +
                         " --threads 1 --foam-time 1");
  ASSERT_EQ(r.exit_code, 0) << r.output;

  // Only the file's points are written: the ball's moved by the shift, the box's kept, the
  // ones between moved by the elastic motion of the pieces.
  const auto original = tf::ascii_points(cfd / "constant" / "polyMesh" / "points");
  const auto moved = tf::ascii_points(cfd / "1" / "polyMesh" / "points");
  ASSERT_EQ(moved.size(), original.size());
  EXPECT_EQ(tf::ascii_points(out / "polyMesh" / "points"), moved);
  std::size_t between = 0;
  for (std::size_t i = 0; i < moved.size(); ++i) {
    const geometry::Vec3 d = moved[i] - original[i];
    const bool on_box = std::abs(std::abs(original[i].x) - 1) < 1e-12 || std::abs(std::abs(original[i].y) - 1) < 1e-12 ||
                        std::abs(std::abs(original[i].z) - 1) < 1e-12;
    if (on_ball[i]) {
      EXPECT_LT(geometry::norm(d - shift), 1e-6) << "ball point " << i;
    } else if (on_box) {
      EXPECT_EQ(moved[i], original[i]) << "box point " << i;
    } else if (geometry::norm(d) > 1e-3) {
      ++between;
    }
  }
  EXPECT_GT(between, 50u);
  // checkMesh passes on the moved case, and hotmesh's figures are checkMesh's.
  EXPECT_GT(check_mesh_polyhedra(tf::check_mesh(cfd, out / "polyMesh", dir / "check")), 100u);
  const nlohmann::json report = nlohmann::json::parse(test::read_text(out / "report.json"));
  expect_as_check_mesh(report["quality"], check_mesh(cfd, "1"));
  EXPECT_GT(report["quality"]["min_scaled_jacobian"].get<double>(), 0.0);
}

}  // namespace
}  // namespace hotmesh::app
