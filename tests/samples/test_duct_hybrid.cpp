// Tests of the duct3d sample's hybrid meshes (issue 24; samples/duct3d/duct-hybrid*): gmsh's
// prism layers on the floor and tetrahedra in the core (duct-hybrid.msh), and prism layers
// upstream, hexahedron layers downstream with pyramids on them, tetrahedra above
// (duct-hybrid-mixed.msh), lifted onto the B-spline floor by make_duct_hybrid. The committed
// meshes are valid, have the cells gmsh made, patches named and tagged as the CAD faces with
// their nodes on them; duct_wall_distance measures triangle floors; and the hybrid cases run by
// hotmesh deform (a few increments) end valid per cell type with the floor on the exact
// deflected floor.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <regex>
#include <string>

#include <nlohmann/json.hpp>

#include "duct_floor.hpp"
#include "floor_distance.hpp"
#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/geometry/surface_distance.hpp"
#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/mesh/element.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/validate.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::samples::duct3d {
namespace {

namespace fs = std::filesystem;
const fs::path kSample = fs::path(HOTMESH_SOURCE_DIR) / "samples" / "duct3d";
constexpr const char* kHybridMesh = "duct-hybrid.msh";

// duct-hybrid.geo: 1 212 floor triangles, 6 prism layers over each, tetrahedra above.
constexpr std::size_t kFloorTriangles = 1212;
constexpr std::size_t kLayers = 6;
constexpr std::size_t kTetrahedra = 6358;

constexpr const char* kMixedMesh = "duct-hybrid-mixed.msh";

// duct-hybrid-mixed.geo: 620 floor triangles upstream and 300 floor quads downstream, 6 layers
// of prisms and hexahedra over them, a pyramid on each hexahedron column's top, tetrahedra.
constexpr std::size_t kMixedFloorTriangles = 620;
constexpr std::size_t kMixedFloorQuads = 300;
constexpr std::size_t kMixedTetrahedra = 10491;

const mesh::Mesh& hybrid() {
  static const mesh::Mesh m = io::read_gmsh(kSample / kHybridMesh);
  return m;
}

const mesh::Mesh& mixed() {
  static const mesh::Mesh m = io::read_gmsh(kSample / kMixedMesh);
  return m;
}

std::map<mesh::ElementType, std::size_t> cells_by_type(const mesh::Mesh& m) {
  std::map<mesh::ElementType, std::size_t> count;
  for (std::size_t c = 0; c < m.cell_count(); ++c) ++count[m.cells.type(c)];
  return count;
}

TEST(DuctHybridMesh, IsValidWithPrismLayersOnTheFloorAndTetrahedraAbove) {
  mesh::Mesh copy = hybrid();
  const auto report = mesh::validate_mesh(copy);
  EXPECT_EQ(report.reoriented_cells, 0u);  // make_duct_hybrid wrote them validated
  EXPECT_EQ(report.interior_patch_faces, 0u);
  const auto count = cells_by_type(copy);
  EXPECT_EQ(count.size(), 2u);
  EXPECT_EQ(count.at(mesh::ElementType::wedge6), kLayers * kFloorTriangles);
  EXPECT_EQ(count.at(mesh::ElementType::tet4), kTetrahedra);
  EXPECT_FALSE(count.contains(mesh::ElementType::pyramid5));  // the layers' top is triangles
  EXPECT_FALSE(count.contains(mesh::ElementType::hex8));
  const auto quality = mesh::summarize_quality(mesh::scaled_jacobians(copy.cells, copy.points));
  EXPECT_EQ(quality.inverted_cells, 0u);
  EXPECT_GT(quality.min_scaled_jacobian, 0.15);  // 0.186, a Delaunay tetrahedron; the prisms 0.741

  // The floor is the prisms' bottom triangles; every prism has a floor triangle under its column.
  const auto* floor = copy.find_patch("floor");
  ASSERT_NE(floor, nullptr);
  EXPECT_EQ(floor->faces.size(), kFloorTriangles);
  for (std::size_t f = 0; f < floor->faces.size(); ++f) EXPECT_EQ(floor->faces.type(f), mesh::ElementType::tri3);
  // The first layer is thin: 0.25 mm (h / 40) where the floor is level, growing by 1.2.
  double lowest_top = kCeiling;
  for (std::size_t c = 0; c < copy.cell_count(); ++c) {
    if (copy.cells.type(c) != mesh::ElementType::tet4) continue;
    for (const auto n : copy.cells.nodes(c)) lowest_top = std::min(lowest_top, copy.points[static_cast<std::size_t>(n)].z);
  }
  EXPECT_GT(lowest_top, 2.0);  // the tetrahedra start above the 2.48 mm of layers (less the floor's dip)
}

TEST(DuctHybridMesh, TheMixedMeshHasEveryCellTypeHexahedronLayersUnderPyramids) {
  mesh::Mesh copy = mixed();
  const auto report = mesh::validate_mesh(copy);
  EXPECT_EQ(report.reoriented_cells, 0u);
  EXPECT_EQ(report.interior_patch_faces, 0u);
  const auto count = cells_by_type(copy);
  EXPECT_EQ(count.size(), 4u);
  EXPECT_EQ(count.at(mesh::ElementType::wedge6), kLayers * kMixedFloorTriangles);
  EXPECT_EQ(count.at(mesh::ElementType::hex8), kLayers * kMixedFloorQuads);
  EXPECT_EQ(count.at(mesh::ElementType::pyramid5), kMixedFloorQuads);  // one on each column's top quad
  EXPECT_EQ(count.at(mesh::ElementType::tet4), kMixedTetrahedra);
  const auto quality = mesh::summarize_quality(mesh::scaled_jacobians(copy.cells, copy.points));
  EXPECT_EQ(quality.inverted_cells, 0u);
  EXPECT_GT(quality.min_scaled_jacobian, 0.07);  // 0.082, a tetrahedron; pyramids 0.175
  const auto* floor = copy.find_patch("floor");
  ASSERT_NE(floor, nullptr);
  std::map<mesh::ElementType, std::size_t> faces;
  for (std::size_t f = 0; f < floor->faces.size(); ++f) ++faces[floor->faces.type(f)];
  EXPECT_EQ(faces[mesh::ElementType::tri3], kMixedFloorTriangles);
  EXPECT_EQ(faces[mesh::ElementType::quad4], kMixedFloorQuads);
  // The quads are downstream of x = 2h, the triangles upstream.
  for (std::size_t f = 0; f < floor->faces.size(); ++f) {
    double x = 0.0;
    for (const auto n : floor->faces.nodes(f)) x += copy.points[static_cast<std::size_t>(n)].x;
    x /= static_cast<double>(floor->faces.nodes(f).size());
    EXPECT_EQ(floor->faces.type(f) == mesh::ElementType::quad4, x > 0.5 * kLength) << f;
  }
}

/// Every patch of `m` named and tagged as its CAD face, its nodes on the face.
void expect_patches_on_cad_faces(const mesh::Mesh& m, const geometry::CadModel& cad) {
  ASSERT_EQ(m.patches.size(), kPatchNames.size());
  for (std::size_t i = 0; i < kPatchNames.size(); ++i) {
    const int face = static_cast<int>(i) + 1;
    const auto* patch = m.find_patch(kPatchNames[i]);
    ASSERT_NE(patch, nullptr) << kPatchNames[i];
    EXPECT_EQ(patch->tag, face);
    geometry::SurfaceDistance surface({cad.face_bspline(face)});
    double worst = 0.0;
    for (const auto n : patch->nodes) {
      worst = std::max(worst, surface.nearest(m.points[static_cast<std::size_t>(n)]).distance);
    }
    EXPECT_LT(worst, 1e-12 * kH) << kPatchNames[i];
  }
  // The side patches hold the layers' quads and the tetrahedra's triangles.
  const auto* side = m.find_patch("side_right");
  std::map<mesh::ElementType, std::size_t> faces;
  for (std::size_t f = 0; f < side->faces.size(); ++f) ++faces[side->faces.type(f)];
  EXPECT_GT(faces[mesh::ElementType::quad4], 0u);
  EXPECT_GT(faces[mesh::ElementType::tri3], 0u);
}

TEST(DuctHybridMesh, PatchesAreTheCadFacesAndTheirNodesLieOnThem) {
  const auto cad = geometry::CadModel::read(kSample / kCadFile, {.unit = geometry::LengthUnit::millimetre});
  {
    SCOPED_TRACE(kHybridMesh);
    expect_patches_on_cad_faces(hybrid(), cad);
  }
  SCOPED_TRACE(kMixedMesh);
  expect_patches_on_cad_faces(mixed(), cad);
}

TEST(DuctHybridWallDistance, MeasuresTriangleFloorsTheUndeformedAndARaisedOne) {
  const auto& m = hybrid();
  const DeflectedFloor cold(floor_surface(), kCold);
  const auto d = floor_distance(m, cold);
  EXPECT_EQ(d.faces, kFloorTriangles);
  EXPECT_LT(d.node.distance, 1e-12 * kH);
  // Flat triangles on the curved floor: the faceting, about that of duct.msh's quads (1.35e-3 h).
  EXPECT_GT(d.hausdorff(), 1e-4 * kH);
  EXPECT_LT(d.hausdorff(), 2e-3 * kH);
  const double offset = 0.02 * kH;
  mesh::Mesh raised = m;
  for (Vec3& p : raised.points) p.z += offset;
  const auto r = floor_distance(raised, cold);
  EXPECT_NEAR(r.node.distance, offset, 1e-3 * offset);
  EXPECT_NEAR(r.hausdorff(), offset, d.hausdorff() + 1e-3 * offset);
  EXPECT_GT(r.hausdorff(), 0.9 * offset);
}

// The two hybrid cases, run by hotmesh deform in a temporary folder with the committed mesh,
// CAD and table, in 4 increments instead of 16 (the same end state, by fewer stages).
test::CommandResult deform(const fs::path& folder, const std::string& yaml) {
  return test::run_command(std::string(HOTMESH_EXE) + " -q deform " + test::shell_quote((folder / yaml).string()));
}

TEST(DuctHybridRuns, PrescribedAndSlidingFloorsOnPrismLayersFollowTheExactFloor) {
  if (test::under_sanitizers()) GTEST_SKIP() << "two 3D runs: seconds in the Release build, minutes here; run there";
  const auto start = std::chrono::steady_clock::now();
  const test::TempDir dir;
  const fs::path folder = dir.path();
  for (const char* file : {kHybridMesh, kCadFile, "floor.csv"}) fs::copy_file(kSample / file, folder / file);
  for (const std::string run : {"duct-hybrid-prescribed", "duct-hybrid-sliding"}) {
    const std::string yaml = test::read_text(kSample / (run + ".yaml"));
    const std::string fewer = std::regex_replace(yaml, std::regex("increments: 16"), "increments: 4");
    ASSERT_NE(fewer, yaml);
    test::write_text(folder / (run + ".yaml"), fewer);
    const auto r = deform(folder, run + ".yaml");
    ASSERT_EQ(r.exit_code, 0) << run << "\n" << r.output;
  }
  const auto& cold = hybrid();
  const DeflectedFloor hot1(floor_surface(), kHot1);
  std::map<std::string, FloorDistance> distance;
  std::map<std::string, nlohmann::json> report;
  for (const std::string run : {"duct-hybrid-prescribed", "duct-hybrid-sliding"}) {
    SCOPED_TRACE(run);
    const auto& j = report[run] = nlohmann::json::parse(test::read_text(folder / (run + "-out") / "report.json"));
    EXPECT_EQ(j["status"], "success");
    EXPECT_EQ(j["inverted_cells"], 0);
    // Per cell type: the counts of the mesh, none inverted, each type near its undeformed
    // worst (measured at 16 increments: prisms 0.741 -> 0.682 prescribed, 0.712 sliding;
    // tetrahedra 0.186 -> 0.173, 0.179).
    const auto& by_type = j["quality"]["by_type"];
    ASSERT_EQ(by_type.size(), 2u) << by_type;
    EXPECT_EQ(by_type["wedge6"]["cells"], kLayers * kFloorTriangles);
    EXPECT_EQ(by_type["tet4"]["cells"], kTetrahedra);
    EXPECT_EQ(by_type["wedge6"]["inverted_cells"], 0);
    EXPECT_EQ(by_type["tet4"]["inverted_cells"], 0);
    EXPECT_GT(by_type["wedge6"]["min_scaled_jacobian"].get<double>(), 0.6);
    EXPECT_GT(by_type["tet4"]["min_scaled_jacobian"].get<double>(), 0.15);
    // The mesh written, checked here rather than trusted from the report.
    const mesh::Mesh moved = io::read_gmsh(folder / (run + "-out") / "deformed.msh");
    const auto quality = mesh::summarize_quality(mesh::scaled_jacobians(moved.cells, moved.points));
    EXPECT_EQ(quality.inverted_cells, 0u);
    const auto d = distance[run] = floor_distance(moved, hot1, {}, &cold);
    std::printf("%s: min scaled Jacobian %.4f (prisms %.4f, tetrahedra %.4f), floor nodes %.3g h, mesh to floor %.3g h, "
                "floor to mesh %.3g h, material points %.3g h\n",
                run.c_str(), quality.min_scaled_jacobian, by_type["wedge6"]["min_scaled_jacobian"].get<double>(),
                by_type["tet4"]["min_scaled_jacobian"].get<double>(), d.node.distance / kH, d.mesh_to_floor.distance / kH,
                d.floor_to_mesh.distance / kH, d.material_point->distance / kH);
    // The floor nodes are off the exact floor by what the field fitted to floor.csv misses
    // (measured 1.6e-3 h, as on the hex duct), the faces by that and the faceting (2.4e-3 h to
    // 2.6e-3 h); bounds about 1.5 times these.
    EXPECT_LT(d.node.distance, 2.5e-3 * kH);
    EXPECT_LT(d.hausdorff(), 4e-3 * kH);
  }
  const auto &prescribed = distance["duct-hybrid-prescribed"], &sliding = distance["duct-hybrid-sliding"];
  // Prescribed nodes sit at their material points, up to the fit; sliding ones leave them.
  EXPECT_LT(prescribed.material_point->distance, 2.5e-3 * kH);
  EXPECT_GT(sliding.material_point->distance, 10 * prescribed.material_point->distance);
  EXPECT_EQ(report["duct-hybrid-sliding"]["sliding_nodes"], 655);  // every floor node
  EXPECT_EQ(report["duct-hybrid-prescribed"]["sliding_nodes"], 0);
  EXPECT_GE(report["duct-hybrid-sliding"]["quality"]["by_type"]["wedge6"]["min_scaled_jacobian"].get<double>(),
            report["duct-hybrid-prescribed"]["quality"]["by_type"]["wedge6"]["min_scaled_jacobian"].get<double>() - 0.01);
  std::printf("hybrid duct runs: %.1f s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

TEST(DuctHybridRuns, TheMixedMeshOfEveryCellTypeMovesWithAPrescribedAndASlidingFloor) {
  if (test::under_sanitizers()) GTEST_SKIP() << "two 3D runs: seconds in the Release build, minutes here; run there";
  const auto start = std::chrono::steady_clock::now();
  const test::TempDir dir;
  const fs::path folder = dir.path();
  for (const char* file : {kMixedMesh, kCadFile, "floor.csv"}) fs::copy_file(kSample / file, folder / file);
  const auto& cold = mixed();
  const DeflectedFloor hot1(floor_surface(), kHot1);
  std::map<std::string, nlohmann::json> report;
  std::map<std::string, FloorDistance> distance;
  for (const std::string run : {"duct-hybrid-mixed-prescribed", "duct-hybrid-mixed-sliding"}) {
    SCOPED_TRACE(run);
    const std::string yaml = test::read_text(kSample / (run + ".yaml"));
    ASSERT_NE(yaml.find("mesh: duct-hybrid-mixed.msh"), std::string::npos);
    const std::string fewer = std::regex_replace(yaml, std::regex("increments: 16"), "increments: 4");
    ASSERT_NE(fewer, yaml);
    test::write_text(folder / (run + ".yaml"), fewer);
    const auto r = deform(folder, run + ".yaml");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto& j = report[run] = nlohmann::json::parse(test::read_text(folder / (run + "-out") / "report.json"));
    EXPECT_EQ(j["status"], "success");
    EXPECT_EQ(j["inverted_cells"], 0);
    // Every type, none inverted, each near its undeformed worst (measured at 16 increments:
    // prisms 0.749 -> 0.752 prescribed, 0.748 sliding; hexahedra 0.708 -> 0.674, 0.700;
    // pyramids 0.175 -> 0.143, 0.155; tetrahedra 0.082 -> 0.070, 0.075).
    const auto& by_type = j["quality"]["by_type"];
    ASSERT_EQ(by_type.size(), 4u) << by_type;
    EXPECT_EQ(by_type["wedge6"]["cells"], kLayers * kMixedFloorTriangles);
    EXPECT_EQ(by_type["hex8"]["cells"], kLayers * kMixedFloorQuads);
    EXPECT_EQ(by_type["pyramid5"]["cells"], kMixedFloorQuads);
    EXPECT_EQ(by_type["tet4"]["cells"], kMixedTetrahedra);
    for (const char* type : {"wedge6", "hex8", "pyramid5", "tet4"}) EXPECT_EQ(by_type[type]["inverted_cells"], 0) << type;
    EXPECT_GT(by_type["wedge6"]["min_scaled_jacobian"].get<double>(), 0.65);
    EXPECT_GT(by_type["hex8"]["min_scaled_jacobian"].get<double>(), 0.6);
    EXPECT_GT(by_type["pyramid5"]["min_scaled_jacobian"].get<double>(), 0.12);
    EXPECT_GT(by_type["tet4"]["min_scaled_jacobian"].get<double>(), 0.06);
    const mesh::Mesh moved = io::read_gmsh(folder / (run + "-out") / "deformed.msh");
    EXPECT_EQ(mesh::summarize_quality(mesh::scaled_jacobians(moved.cells, moved.points)).inverted_cells, 0u);
    const auto d = distance[run] = floor_distance(moved, hot1, {}, &cold);
    std::printf("%s: floor nodes %.3g h, mesh to floor %.3g h, floor to mesh %.3g h, material points %.3g h\n",
                run.c_str(), d.node.distance / kH, d.mesh_to_floor.distance / kH, d.floor_to_mesh.distance / kH,
                d.material_point->distance / kH);
    // Measured: nodes 1.42e-3 h; faces 3.1e-3 to 3.2e-3 h (the quads facet the bulge more
    // than the triangles: 3.3e-3 h with every node exactly on the exact floor).
    EXPECT_LT(d.node.distance, 2.5e-3 * kH);
    EXPECT_LT(d.hausdorff(), 5e-3 * kH);
  }
  EXPECT_LT(distance["duct-hybrid-mixed-prescribed"].material_point->distance, 2.5e-3 * kH);
  EXPECT_GT(distance["duct-hybrid-mixed-sliding"].material_point->distance,
            10 * distance["duct-hybrid-mixed-prescribed"].material_point->distance);
  EXPECT_EQ(report["duct-hybrid-mixed-sliding"]["sliding_nodes"], 659);  // every floor node, triangles' and quads'
  std::printf("mixed duct runs: %.1f s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace
}  // namespace hotmesh::samples::duct3d
