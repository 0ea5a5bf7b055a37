// Tests of hotmesh::io::read_case / parse_case: a full case parses into the right values with
// absolute paths; defaults apply; every rule of the schema gives
// "<case file>:<line>: <key path>: ..." and all problems of a file are reported together. The
// patches (roles, deflections, axis, periodic pairs, the case against the mesh) are in
// test_case_patches.cpp.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "case_file_fixture.hpp"

namespace hotmesh::io {
namespace {

using namespace test_case;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::SizeIs;
using ::testing::StartsWith;

// The example of the project issue, with the partner per_hi added (a pair needs both sides).
constexpr std::string_view kFullExample =
    "# full example\n"
    "mesh: mesh.msh\n"
    "cad: part.step\n"
    "output: out\n"
    "axis: {origin: [0, 0, 1.5], direction: [1, 0, 0]}\n"
    "solver: {increments: 8, newton_tolerance: 1.0e-5, max_newton_iterations: 20,\n"
    "         pcg_tolerance: 1.0e-2, max_pcg_iterations: 1000, threads: 2}\n"
    "material: {alpha_s: 2.0, alpha_v: 0.1}\n"
    "patches:\n"
    "  left:   {role: fixed}\n"
    "  right:  {role: slip}\n"
    "  top:    {role: sliding}\n"
    "  bottom: {role: sliding, deflection: {file: ramp.csv, degree: 1}}\n"
    "  blade:  {role: prescribed, deflection: {file: blade.csv, faces: [3, 4], degree: 3}}\n"
    "  inlet:  {role: passive}\n"
    "  per_lo: {role: periodic, partner: per_hi, angle_deg: 3.6}\n"
    "  per_hi: {role: periodic}\n";

TEST_F(CaseFile, ParsesFullExample) {
  const Case c = parse(kFullExample);
  EXPECT_EQ(c.file, case_path());
  EXPECT_EQ(c.mesh, dir / "mesh.msh");
  EXPECT_EQ(c.cad, dir / "part.step");
  EXPECT_EQ(c.output, dir / "out");
  ASSERT_TRUE(c.axis.has_value());
  EXPECT_EQ(c.axis->origin(), (geometry::Vec3{0, 0, 1.5}));
  EXPECT_EQ(c.axis->direction(), (geometry::Vec3{1, 0, 0}));
  EXPECT_EQ(c.solver.increments, 8);
  EXPECT_EQ(c.solver.newton_tolerance, 1e-5);
  EXPECT_EQ(c.solver.max_newton_iterations, 20);
  EXPECT_EQ(c.solver.pcg_tolerance, 1e-2);
  EXPECT_EQ(c.solver.max_pcg_iterations, 1000);
  EXPECT_EQ(c.threads, 2);
  EXPECT_EQ(c.material.alpha_s, 2.0);
  EXPECT_EQ(c.material.alpha_v, 0.1);
  EXPECT_EQ(c.patches_line, 9u);

  ASSERT_THAT(c.patches, SizeIs(8));
  std::vector<std::string> names;
  std::vector<std::string_view> roles;
  for (const PatchSpec& p : c.patches) {
    names.push_back(p.name);
    roles.push_back(to_string(p.role));
  }
  EXPECT_THAT(names, ElementsAre("left", "right", "top", "bottom", "blade", "inlet", "per_lo", "per_hi"));
  EXPECT_THAT(roles, ElementsAre("fixed", "slip", "sliding", "sliding", "prescribed", "passive", "periodic", "periodic"));

  const PatchSpec* top = c.find_patch("top");
  ASSERT_NE(top, nullptr);
  EXPECT_EQ(top->line, 12u);
  EXPECT_FALSE(top->deflection.has_value());

  const PatchSpec* bottom = c.find_patch("bottom");
  ASSERT_TRUE(bottom->deflection.has_value());
  EXPECT_EQ(bottom->deflection->file, dir / "ramp.csv");
  EXPECT_EQ(bottom->deflection->degree, 1);
  EXPECT_TRUE(bottom->deflection->faces.empty());
  EXPECT_EQ(bottom->deflection->samples.frame, geometry::SampleFrame::meridional);
  EXPECT_EQ(bottom->deflection->samples.size(), 2u);
  EXPECT_EQ(bottom->deflection->line, 13u);

  const PatchSpec* blade = c.find_patch("blade");
  ASSERT_TRUE(blade->deflection.has_value());
  EXPECT_EQ(blade->deflection->degree, 3);
  EXPECT_THAT(blade->deflection->faces, ElementsAre(3, 4));
  EXPECT_THAT(blade->deflection->samples.ids, ElementsAre(1, 2, 3, 4));
  EXPECT_EQ(blade->deflection->samples.source, (dir / "blade.csv").string());

  const PatchSpec* lo = c.find_patch("per_lo");
  EXPECT_EQ(lo->partner, "per_hi");
  EXPECT_EQ(lo->angle_deg, 3.6);
  const PatchSpec* hi = c.find_patch("per_hi");
  EXPECT_EQ(hi->partner, "per_lo");  // filled in from the declaring side
  EXPECT_EQ(hi->angle_deg, 0.0);
  EXPECT_EQ(c.find_patch("outlet"), nullptr);

  EXPECT_THAT(c.inputs(), ElementsAre(case_path(), dir / "mesh.msh", dir / "part.step", dir / "ramp.csv",
                                      dir / "blade.csv"));
}

TEST_F(CaseFile, AppliesDefaults) {
  const Case c = parse(std::string(kBase) + "solver:\nmaterial: {}\n");
  const deform::SolverOptions solver;
  const deform::MaterialOptions material;
  EXPECT_EQ(c.solver.increments, solver.increments);
  EXPECT_EQ(c.solver.newton_tolerance, solver.newton_tolerance);
  EXPECT_EQ(c.solver.max_newton_iterations, solver.max_newton_iterations);
  EXPECT_EQ(c.solver.pcg_tolerance, solver.pcg_tolerance);
  EXPECT_EQ(c.solver.max_pcg_iterations, solver.max_pcg_iterations);
  EXPECT_EQ(c.threads, 0);  // all cores
  EXPECT_EQ(c.material.alpha_s, material.alpha_s);
  EXPECT_EQ(c.material.alpha_v, material.alpha_v);
  EXPECT_EQ(c.material.law, material.law);
  EXPECT_EQ(c.material.drop_jacobian, material.drop_jacobian);
  EXPECT_EQ(c.solver.max_increment_splits, solver.max_increment_splits);
  EXPECT_EQ(c.solver.linear, deform::LinearSolverKind::automatic);  // the tool picks
  EXPECT_EQ(c.solver.amg, deform::AmgPackage::gamg);
  EXPECT_EQ(c.solver.forcing, deform::ForcingTerm::fixed);
  EXPECT_TRUE(c.pictures.empty());
  EXPECT_EQ(c.output, dir / "case-out");
  EXPECT_FALSE(c.cad.has_value());
  EXPECT_FALSE(c.axis.has_value());
  ASSERT_THAT(c.patches, SizeIs(1));
  EXPECT_EQ(c.patches[0].role, PatchRole::fixed);
  EXPECT_EQ(c.patches_line, 2u);
  EXPECT_THAT(c.inputs(), ElementsAre(case_path(), dir / "mesh.msh"));
}

TEST_F(CaseFile, ReadsOutputAsFolderOrMapWithSeries) {
  EXPECT_FALSE(parse(std::string(kBase) + "output: hot\n").series);
  const Case c = parse(std::string(kBase) + "output: {folder: hot, series: true}\n");
  EXPECT_EQ(c.output, dir / "hot");
  EXPECT_TRUE(c.series);
  const Case d = parse(std::string(kBase) + "output: {series: yes}\n");
  EXPECT_EQ(d.output, dir / "case-out");
  EXPECT_TRUE(d.series);
  const auto lines = lines_of(error_of(std::string(kBase) + "output: {folder: hot, series: often, movie: true}\n"));
  ASSERT_THAT(lines, SizeIs(2));
  EXPECT_THAT(lines[0], HasSubstr("movie"));
  EXPECT_THAT(lines[1], HasSubstr("output.series"));
}

TEST_F(CaseFile, ReadsStiffnessLawSplitsAndPictures) {
  const Case c = parse(std::string(kBase) +
                       "material: {law: inverse_volume, drop_jacobian: false}\n"
                       "solver: {max_increment_splits: 0}\n"
                       "pictures:\n  ramp: [0.8, 1.2, 0, 0.6]\n  all-of_it: [0, 2, 0, 1]\n");
  EXPECT_EQ(c.material.law, deform::StiffnessLaw::inverse_volume);
  EXPECT_FALSE(c.material.drop_jacobian);
  EXPECT_EQ(c.solver.max_increment_splits, 0);
  ASSERT_THAT(c.pictures, SizeIs(2));
  EXPECT_EQ(c.pictures[0].name, "ramp");
  EXPECT_EQ(c.pictures[0].xmax, 1.2);
  EXPECT_EQ(c.pictures[0].ymax, 0.6);
  EXPECT_EQ(c.pictures[0].line, 7u);
  EXPECT_EQ(c.pictures[1].name, "all-of_it");
}

TEST_F(CaseFile, ReadsDeflectionFormAndRestart) {
  test::write_text(dir / "restart.hmr", "x");
  const Case c = parse(std::string(kBase) + "  ramp: {role: sliding, deflection: {file: plane.csv, form: displacement}}\n" +
                       "restart: restart.hmr\n");
  EXPECT_EQ(c.find_patch("ramp")->deflection->form, geometry::DeflectionForm::displacement);
  EXPECT_EQ(c.find_patch("wall")->deflection, std::nullopt);
  ASSERT_TRUE(c.restart.has_value());
  EXPECT_EQ(*c.restart, dir / "restart.hmr");
  EXPECT_THAT(c.inputs(), ::testing::Contains(dir / "restart.hmr"));
  EXPECT_EQ(c.length_unit, geometry::LengthUnit::metre);
  EXPECT_EQ(parse(std::string(kBase) + "length_unit: mm\n").length_unit, geometry::LengthUnit::millimetre);
  EXPECT_THAT(error_with("length_unit: furlong\n"), HasSubstr("length_unit: expected one of m, mm, cm, um, in, ft"));
  const std::string error = error_with("  ramp: {role: sliding, deflection: {file: plane.csv, form: spline}}\nrestart: nowhere.hmr\n");
  EXPECT_THAT(error, HasSubstr(at(5) + "restart: "));
  EXPECT_THAT(error, HasSubstr("patches.ramp.deflection.form: expected one of curve, displacement, got 'spline'"));
}

TEST_F(CaseFile, ReadsLinearSolverMultigridAndForcing) {
  const Case c = parse(std::string(kBase) + "solver: {linear: amg, amg: hypre, forcing: eisenstat-walker}\n");
  EXPECT_EQ(c.solver.linear, deform::LinearSolverKind::amg);
  EXPECT_EQ(c.solver.amg, deform::AmgPackage::hypre);
  EXPECT_EQ(c.solver.forcing, deform::ForcingTerm::eisenstat_walker);
  const Case jacobi = parse(std::string(kBase) + "solver:\n  linear: jacobi-pcg\n  amg: gamg\n  forcing: fixed\n");
  EXPECT_EQ(jacobi.solver.linear, deform::LinearSolverKind::jacobi_pcg);
  EXPECT_EQ(jacobi.solver.amg, deform::AmgPackage::gamg);
  EXPECT_EQ(jacobi.solver.forcing, deform::ForcingTerm::fixed);
  EXPECT_EQ(parse(std::string(kBase) + "solver: {linear: auto}\n").solver.linear, deform::LinearSolverKind::automatic);
}

TEST_F(CaseFile, RejectsUnknownLinearSolverMultigridAndForcing) {
  const std::string error = error_with(
      "solver:\n"
      "  linear: cholesky\n"
      "  amg: [gamg]\n"
      "  forcing: adaptive\n");
  EXPECT_THAT(error, HasSubstr(at(5) + "solver.linear: expected one of auto, jacobi-pcg, amg, direct, icc, got 'cholesky'"));
  EXPECT_THAT(error, HasSubstr(at(6) + "solver.amg: expected one of gamg, hypre, got a list"));
  EXPECT_THAT(error, HasSubstr(at(7) + "solver.forcing: expected one of fixed, eisenstat-walker, got 'adaptive'"));
}

TEST_F(CaseFile, ReadsWhatTheMultigridKeepsAndRefusesInterpolationForHypre) {
  EXPECT_EQ(parse(std::string(kBase)).solver.amg_reuse, deform::AmgReuse::automatic);
  EXPECT_EQ(parse(std::string(kBase) + "solver: {linear: amg, amg_reuse: interpolation}\n").solver.amg_reuse,
            deform::AmgReuse::interpolation);
  EXPECT_EQ(parse(std::string(kBase) + "solver: {linear: amg, amg_reuse: adaptive}\n").solver.amg_reuse,
            deform::AmgReuse::adaptive);
  EXPECT_EQ(parse(std::string(kBase) + "solver: {linear: amg, amg: hypre, amg_reuse: preconditioner}\n").solver.amg_reuse,
            deform::AmgReuse::preconditioner);
  const std::string error = error_with(
      "solver:\n"
      "  amg: hypre\n"
      "  amg_reuse: interpolation\n"
      "  linear: amg\n");
  EXPECT_THAT(error, HasSubstr(at(6) + "solver.amg_reuse: interpolation is kept by amg: gamg only"));
  EXPECT_THAT(error_with("solver: {amg_reuse: always}\n"),
              HasSubstr("solver.amg_reuse: expected one of auto, adaptive, preconditioner, interpolation, none, got 'always'"));
}

TEST_F(CaseFile, RejectsBadLawFlagAndPictures) {
  const std::string error = error_with(
      "material: {law: spring, drop_jacobian: maybe}\n"
      "pictures:\n  bad/name: [0, 1, 0, 1]\n  flat: [0, 1, 1, 1]\n  short: [0, 1]\n");
  EXPECT_THAT(error, HasSubstr(at(4) + "material.law: expected one of shape_volume, uniform, inverse_volume, got 'spring'"));
  EXPECT_THAT(error, HasSubstr(at(4) + "material.drop_jacobian: expected true or false, got 'maybe'"));
  EXPECT_THAT(error, HasSubstr(at(6) + "pictures.bad/name: picture names become file names"));
  EXPECT_THAT(error, HasSubstr(at(7) + "pictures.flat: the view needs xmin < xmax and ymin < ymax"));
  EXPECT_THAT(error, HasSubstr(at(8) + "pictures.short: expected a view [xmin, xmax, ymin, ymax], got a list"));
}

TEST_F(CaseFile, AcceptsQuotedTextAndParsesWithoutCaseFileOnDisk) {
  const Case c = parse_case("mesh: \"mesh.msh\"\npatches:\n  'wall': {role: 'slip'}\n", dir / "virtual.yaml");
  EXPECT_EQ(c.file, dir / "virtual.yaml");
  EXPECT_EQ(c.mesh, dir / "mesh.msh");
  EXPECT_EQ(c.output, dir / "virtual-out");
  EXPECT_EQ(c.find_patch("wall")->role, PatchRole::slip);
}

TEST_F(CaseFile, ResolvesPathsAgainstCaseFolderAndNormalisesThem) {
  fs::create_directories(dir / "run" / "sub");
  fs::create_directories(dir / "meshes");
  test::write_text(dir / "meshes" / "m.msh", "x");
  const fs::path table = dir / "plane.csv";
  const std::string yaml = "mesh: ../meshes/./m.msh\noutput: results/../res\npatches:\n  wall: {role: sliding, "
                           "deflection: {file: " + table.string() + "}}\n";
  test::write_text(dir / "run" / "case.yaml", yaml);
  const Case c = read_case(dir / "run" / "sub" / ".." / "case.yaml");
  EXPECT_EQ(c.file, dir / "run" / "case.yaml");
  EXPECT_EQ(c.mesh, dir / "meshes" / "m.msh");
  EXPECT_EQ(c.output, dir / "run" / "res");
  EXPECT_EQ(c.patches[0].deflection->file, table);  // absolute paths stay as they are
  EXPECT_TRUE(c.mesh.is_absolute());
}

TEST_F(CaseFile, ReportsInvalidYamlWithParserLine) {
  const std::string error = error_of("mesh: mesh.msh\npatches: {wall: [1, 2}\n");
  EXPECT_THAT(error, StartsWith(at(2) + "invalid YAML: "));
  EXPECT_THAT(lines_of(error), SizeIs(1));
}

TEST_F(CaseFile, RejectsEmptyFileAndNonMapDocument) {
  EXPECT_THAT(error_of("# only a comment\n"), StartsWith(case_path().string() + ": the case file is empty"));
  EXPECT_EQ(error_of("\n- mesh.msh\n"), at(2) + "expected a map of keys (mesh, patches, ...), got a list");
}

TEST_F(CaseFile, RequiresMeshAndPatches) {
  const auto lines = lines_of(error_of("# c\ncad: part.step\n"));
  ASSERT_THAT(lines, SizeIs(2));
  EXPECT_EQ(lines[0], at(2) + "mesh: missing; give the mesh file, e.g. `mesh: mesh.msh`");
  EXPECT_THAT(lines[1], StartsWith(at(2) + "patches: missing; give every mesh patch a role"));
  EXPECT_THAT(error_of("mesh: mesh.msh\npatches: {}\n"), StartsWith(at(2) + "patches: is empty"));
}

TEST_F(CaseFile, RejectsUnknownTopLevelKey) {
  EXPECT_EQ(error_with("mehs: x\n"), at(4) + "mehs: unknown key (did you mean 'mesh'?); allowed at the top level: "
                                             "mesh, cad, length_unit, output, axis, solver, material, quality, patches, pictures, restart");
  EXPECT_EQ(error_with("colour: red\n"), at(4) + "colour: unknown key; allowed at the top level: mesh, cad, "
                                                 "length_unit, output, axis, solver, material, quality, patches, pictures, restart");
}

TEST_F(CaseFile, RejectsUnknownSolverKey) {
  EXPECT_THAT(error_with("solver:\n  increments: 4\n  newton_tol: 1e-3\n"),
              StartsWith(at(6) + "solver.newton_tol: unknown key (did you mean 'newton_tolerance'?); allowed in "
                                 "solver: increments, newton_tolerance,"));
  EXPECT_THAT(error_with("material: {alpha: 1}\n"), StartsWith(at(4) + "material.alpha: unknown key"));
  EXPECT_THAT(error_with("axis: {origin: [0, 0, 0], direction: [0, 0, 1], up: [0, 1, 0]}\n"),
              StartsWith(at(4) + "axis.up: unknown key; allowed in axis: origin, direction"));
}

TEST_F(CaseFile, RejectsUnknownPatchKey) {
  EXPECT_EQ(error_with("  inlet: {role: passive, colour: red}\n"),
            at(4) + "patches.inlet.colour: unknown key; allowed in patches.inlet: role, deflection, partner, angle_deg, features");
}

TEST_F(CaseFile, RejectsUnknownDeflectionKey) {
  EXPECT_EQ(error_with("  ramp:\n    role: sliding\n    deflection:\n      file: plane.csv\n      degre: 2\n"),
            at(8) + "patches.ramp.deflection.degre: unknown key (did you mean 'degree'?); allowed in "
                    "patches.ramp.deflection: file, calculix, degree, faces, edges, form, mode");
}

TEST_F(CaseFile, RejectsRepeatedKeys) {
  EXPECT_EQ(error_with("mesh: other.msh\n"), at(4) + "mesh: given twice (first on line 1); keep one");
  EXPECT_EQ(error_with("  wall: {role: slip}\n"), at(4) + "patches.wall: given twice (first on line 3); keep one");
}

TEST_F(CaseFile, RejectsMissingFiles) {
  const auto lines = lines_of(error_of(
      "mesh: nowhere/mesh.msh\n"
      "cad: part.stp\n"
      "patches:\n"
      "  ramp: {role: prescribed, deflection: {file: ramp2.csv}}\n"));
  ASSERT_THAT(lines, SizeIs(3));
  EXPECT_EQ(lines[0], at(1) + "mesh: file not found: " + (dir / "nowhere" / "mesh.msh").string() +
                          " (relative paths start from the case file's folder)");
  EXPECT_THAT(lines[1], StartsWith(at(2) + "cad: file not found: " + (dir / "part.stp").string()));
  EXPECT_THAT(lines[2], StartsWith(at(4) + "patches.ramp.deflection.file: file not found: " +
                                   (dir / "ramp2.csv").string()));
}

// A mesh may be a folder (OpenFOAM's polyMesh; its reader checks what is in it), the other
// inputs not.
TEST_F(CaseFile, RejectsFolderAsFileAndWrongCadFormat) {
  fs::create_directories(dir / "meshdir");
  const auto lines = lines_of(
      error_of("mesh: meshdir\ncad: part.stl\noutput: mesh.msh\nrestart: meshdir\npatches: {w: {role: fixed}}\n"));
  ASSERT_THAT(lines, SizeIs(3));
  EXPECT_EQ(lines[0], at(2) + "cad: 'part.stl' is not a CAD file hotmesh reads; expected .step, .stp, .iges or .igs");
  EXPECT_THAT(lines[1], StartsWith(at(3) + "output: " + (dir / "mesh.msh").string() + " exists and is not a folder"));
  EXPECT_EQ(lines[2], at(4) + "restart: " + (dir / "meshdir").string() + " is a folder, expected a file");
}

TEST_F(CaseFile, RejectsWrongTypes) {
  const auto lines = lines_of(error_of(
      "mesh: [a.msh, b.msh]\n"                       // 1
      "solver: [1, 2]\n"                             // 2
      "material: {alpha_s: \"2\", alpha_v: high}\n"  // 3
      "axis: {origin: [0, 0], direction: 1}\n"       // 4
      "patches:\n"                                   // 5
      "  a: fixed\n"                                 // 6
      "  b: {role: [fixed]}\n"                       // 7
      "  c: {role: sliding, deflection: plane.csv}\n"  // 8
      "  d: {role: prescribed, deflection: {file: plane.csv, faces: 3, degree: 2.0}}\n"  // 9
      "cad: part.step\n"));                          // 10
  ASSERT_THAT(lines, SizeIs(11));
  EXPECT_EQ(lines[0], at(1) + "mesh: expected the mesh file name, got a list");
  EXPECT_THAT(lines[1], StartsWith(at(2) + "solver: expected a map of solver options (increments, "));
  EXPECT_THAT(lines[1], HasSubstr("got a list"));
  EXPECT_EQ(lines[2], at(3) + "material.alpha_s: expected a number, got the text \"2\"");
  EXPECT_EQ(lines[3], at(3) + "material.alpha_v: expected a number, got 'high'");
  EXPECT_EQ(lines[4], at(4) + "axis.origin: expected a list of 3 numbers [x, y, z], got a list of 2");
  EXPECT_EQ(lines[5], at(4) + "axis.direction: expected a list of 3 numbers [x, y, z], got '1'");
  EXPECT_EQ(lines[6], at(6) + "patches.a: expected a map {role: ...}, got 'fixed'");
  EXPECT_EQ(lines[7], at(7) + "patches.b.role: expected a role (one of fixed, prescribed, slip, sliding, passive, "
                              "periodic), got a list");
  EXPECT_THAT(lines[8], StartsWith(at(8) + "patches.c.deflection: expected a map {file: <table.csv>"));
  EXPECT_EQ(lines[9], at(9) + "patches.d.deflection.degree: expected a whole number, got '2.0'");
  EXPECT_EQ(lines[10], at(9) + "patches.d.deflection.faces: expected a list of CAD face numbers (>= 1), e.g. [3, 4], "
                               "got '3'");
}

TEST_F(CaseFile, RejectsWrongTypeForPatchesAndNumbers) {
  EXPECT_EQ(error_of("mesh: mesh.msh\npatches: [wall, inlet]\n"),
            at(2) + "patches: expected a map of patch names to {role: ...}, got a list");
  EXPECT_EQ(error_with("solver: {increments: \"16\"}\n"), at(4) + "solver.increments: expected an integer, got the text \"16\"");
  EXPECT_EQ(error_with("solver: {threads: all}\n"), at(4) + "solver.threads: expected an integer, got 'all'");
}

TEST_F(CaseFile, RejectsValuesOutOfRange) {
  const auto lines = lines_of(error_with(
      "solver:\n"                        // 4
      "  increments: 0\n"                // 5
      "  newton_tolerance: 1\n"          // 6
      "  max_newton_iterations: 3.5\n"   // 7
      "  pcg_tolerance: -1e-3\n"         // 8
      "  max_pcg_iterations: 0\n"        // 9
      "  threads: -1\n"                  // 10
      "material:\n"                      // 11
      "  alpha_s: 0\n"                   // 12
      "  alpha_v: -0.1\n"                // 13
      "axis: {origin: [0, .nan, 0], direction: [0, 0, 0]}\n"));  // 14
  ASSERT_THAT(lines, SizeIs(10));
  EXPECT_EQ(lines[0], at(5) + "solver.increments: must be an integer >= 1, got 0");
  EXPECT_EQ(lines[1], at(6) + "solver.newton_tolerance: must be at least 1e-14 (what double precision reaches) and below 1, got 1");
  EXPECT_EQ(lines[2], at(7) + "solver.max_newton_iterations: expected a whole number, got '3.5'");
  EXPECT_EQ(lines[3], at(8) + "solver.pcg_tolerance: must be at least 1e-14 (what double precision reaches) and below 1, got -1e-3");
  EXPECT_EQ(lines[4], at(9) + "solver.max_pcg_iterations: must be an integer >= 1, got 0");
  EXPECT_EQ(lines[5], at(10) + "solver.threads: must be an integer >= 0, got -1");
  EXPECT_EQ(lines[6], at(12) + "material.alpha_s: must be > 0, got 0");
  EXPECT_EQ(lines[7], at(13) + "material.alpha_v: must be >= 0, got -0.1");
  EXPECT_EQ(lines[8], at(14) + "axis.origin[1]: must be a finite number, got .nan");
  EXPECT_THAT(lines[9], StartsWith(at(14) + "axis.direction: must not be [0, 0, 0]"));
}

// Issue 18, item 8: `pcg_tolerance: 1e-300` ran on and was reported as a stiffness that is
// not positive definite.
TEST_F(CaseFile, RejectsTolerancesBeyondDoublePrecision) {
  const auto lines = lines_of(error_with("solver: {pcg_tolerance: 1e-300, newton_tolerance: 1e-15}\n"));
  ASSERT_THAT(lines, SizeIs(2));
  EXPECT_EQ(lines[0], at(4) + "solver.newton_tolerance: must be at least 1e-14 (what double precision reaches) and "
                              "below 1, got 1e-15");
  EXPECT_THAT(lines[1], HasSubstr("solver.pcg_tolerance: must be at least 1e-14"));
  EXPECT_EQ(parse(std::string(kBase) + "solver: {pcg_tolerance: 1e-14}\n").solver.pcg_tolerance, 1e-14);
}

TEST_F(CaseFile, RefusesIncrementCountsBeyondTheBoundSayingWhatToDo) {
  // Issue 18: `increments: 1000000000` took more than 13 GB before increment 1.
  const auto lines = lines_of(error_with(
      "solver:\n"                          // 4
      "  increments: 1000000000\n"         // 5
      "  max_increment_splits: 1000\n"));  // 6
  ASSERT_THAT(lines, SizeIs(2));
  EXPECT_THAT(lines[0], StartsWith(at(5) + "solver.increments: must be at most 10000, got 1000000000: "));
  EXPECT_THAT(lines[0], HasSubstr("the paper's cases take 16"));
  EXPECT_THAT(lines[0], HasSubstr("max_increment_splits"));
  EXPECT_EQ(lines[1], at(6) + "solver.max_increment_splits: must be an integer from 0 to 20, got 1000");
  EXPECT_THAT(error_with("solver: {increments: 10001}\n"), HasSubstr("must be at most 10000, got 10001"));
  EXPECT_THAT(error_with("solver: {increments: 99999999999}\n"), HasSubstr("must be at most 10000"));
  const Case c = parse(std::string(kBase) + "solver: {increments: 10000, max_increment_splits: 20}\n");
  EXPECT_EQ(c.solver.increments, kMaxIncrements);
  EXPECT_EQ(c.solver.max_increment_splits, kMaxIncrementSplits);
}

TEST_F(CaseFile, RejectsDeflectionOptionsOutOfRange) {
  const auto lines = lines_of(error_with(
      "  blade: {role: prescribed, deflection: {file: blade.csv, degree: 6, faces: [2, 0, 2]}}\n"
      "cad: part.step\n"));
  ASSERT_THAT(lines, SizeIs(3));
  EXPECT_EQ(lines[0], at(4) + "patches.blade.deflection.degree: must be an integer from 1 to 5, got 6");
  EXPECT_EQ(lines[1], at(4) + "patches.blade.deflection.faces[1]: must be an integer >= 1, got 0");
  EXPECT_EQ(lines[2], at(4) + "patches.blade.deflection.faces[2]: face 2 is listed twice");
}

TEST_F(CaseFile, RejectsDegreeHigherThanSamplesAllow) {
  EXPECT_EQ(error_with("  ramp: {role: sliding, deflection: {file: plane.csv, degree: 2}}\n"),
            at(4) + "patches.ramp.deflection.degree: a degree-2 curve needs at least 3 samples, the table has 2");
}

TEST_F(CaseFile, ReportsAllProblemsInFileOrder) {
  const auto lines = lines_of(error_of(
      "patches:\n"                                         // 1
      "  wall: {role: fixd}\n"                             // 2
      "  blade: {role: prescribed}\n"                      // 3
      "solver: {increments: 0, threads: 1.5}\n"            // 4
      "mesh: missing.msh\n"                                // 5
      "extra: 1\n"));                                      // 6
  ASSERT_THAT(lines, SizeIs(6));
  EXPECT_THAT(lines[0], StartsWith(at(2) + "patches.wall.role: unknown role 'fixd'; expected one of fixed, "));
  EXPECT_EQ(lines[1], at(3) + "patches.blade.deflection: missing; a prescribed patch needs `deflection: {file: <table.csv>}`");
  EXPECT_THAT(lines[2], StartsWith(at(4) + "solver.increments: "));
  EXPECT_THAT(lines[3], StartsWith(at(4) + "solver.threads: "));
  EXPECT_THAT(lines[4], StartsWith(at(5) + "mesh: file not found"));
  EXPECT_THAT(lines[5], StartsWith(at(6) + "extra: unknown key"));
}

TEST_F(CaseFile, ReadCaseReportsUnreadableFile) {
  EXPECT_THROW(read_case(dir / "absent.yaml"), InputError);
}

TEST_F(CaseFile, RoleNames) {
  EXPECT_EQ(to_string(PatchRole::prescribed), "prescribed");
  EXPECT_EQ(to_string(PatchRole::periodic), "periodic");
}

}  // namespace
}  // namespace hotmesh::io
