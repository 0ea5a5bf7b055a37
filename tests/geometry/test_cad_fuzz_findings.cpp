// Tests of CAD files that crashed or hung hotmesh while it was fuzzed (fuzz/fuzz_cad.cpp,
// docs/fuzzing.md), kept in tests/data/fuzz/. Mutations of the real I-DEAS and CATIA cones
// (IGES) made OpenCASCADE follow a null pointer (a segmentation fault, exit 139) before the
// readers turned its faults into errors (issue 18, item 3); now each is read, or refused as a
// user error naming the file. Mutations of STEP files that define an entity number twice made
// OpenCASCADE read uninitialised memory and, now and then, spin for ever; they are refused
// before OpenCASCADE parses them.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/core/input_error.hpp"
#include "test_support.hpp"

#include <string>

namespace hotmesh::geometry {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;
using ::testing::ThrowsMessage;

// A B-spline curve record whose parameters were damaged faulted while the file was parsed
// (IGESGeom_BSplineCurve::Init). The record is left out; the cone's two faces do not need it.
TEST(CadFuzzFindings, IgesBsplineCurveRecordThatFaultedWhileParsing) {
  const CadModel model = CadModel::read(test::data_path("fuzz/iges-bspline-curve-record.igs"));
  EXPECT_EQ(model.faces().size(), 2u);
}

// Likewise a B-spline surface record (IGESGeom_BSplineSurface::Init): nothing is left to read.
TEST(CadFuzzFindings, IgesBsplineSurfaceRecordThatFaultedWhileParsing) {
  const auto file = test::data_path("fuzz/iges-bspline-surface-record.igs");
  EXPECT_THAT([&] { CadModel::read(file); }, ThrowsMessage<InputError>(HasSubstr(file.string() + ": ")));
}

// A solid's face without its loops faulted in the translation (IGESSolid_Face::NbLoops).
TEST(CadFuzzFindings, IgesFaceWithoutLoopsThatFaultedInTheTranslation) {
  const auto file = test::data_path("fuzz/iges-face-without-loops.igs");
  EXPECT_THAT([&] { CadModel::read(file); },
              ThrowsMessage<InputError>(HasSubstr(file.string() + ": the IGES file is damaged")));
}

// The CATIA bolt with #268 renumbered #18: valgrind showed OpenCASCADE's uninitialised read on
// every read of it.
TEST(CadFuzzFindings, StepEntityDefinedTwice) {
  const auto file = test::data_path("fuzz/step-entity-defined-twice.stp");
  EXPECT_THAT([&] { CadModel::read(file); },
              ThrowsMessage<InputError>(HasSubstr(file.string() +
                                                  ":49: the STEP file is damaged: entity #18 is defined a second "
                                                  "time (first on line 48)")));
}

// screw.step with #568 renumbered #136: the fuzz target spun on it for over a minute.
TEST(CadFuzzFindings, StepOnWhichTheReaderSpun) {
  const auto file = test::data_path("fuzz/step-spun-in-set-entity-numbers.step");
  EXPECT_THAT([&] { CadModel::read(file); },
              ThrowsMessage<InputError>(HasSubstr(file.string() + ":815: the STEP file is damaged: entity #136")));
}

/// The CATIA bolt with `extra` inserted before its first entity.
std::string bolt_with(const std::string& extra) {
  std::string text = test::read_text(test::data_path("cad/bug3883_xr2-ct-214_bolt.stp"));
  text.insert(text.find("#5=PRODUCT("), extra);
  return text;
}

// A number counts as defined only at the start of a statement: not in strings (with '' for a
// quote, and ';' inside), comments or references, and whitespace or comments may stand around
// the '='.
TEST(CadFuzzFindings, StepEntityNumbersAreReadAsTheStandardWritesThem) {
  test::TempDir dir;
  const auto clean = dir / "clean.stp";
  test::write_text(clean, bolt_with("/* #5=PRODUCT(); */\n#900=PRODUCT('it''s ;#5=',' ',' ',(#2)) ;\n"));
  EXPECT_GT(CadModel::read(clean).faces().size(), 0u);

  for (const std::string& repeat : {std::string("#5 = PRODUCT('x',' ',' ',(#2)) ;\n"),
                                    std::string("  #5\n=PRODUCT('x',' ',' ',(#2)) ;\n"),
                                    std::string("#5/* a comment */=PRODUCT('x',' ',' ',(#2)) ;\n")}) {
    const auto file = dir / "repeat.stp";
    test::write_text(file, bolt_with(repeat));
    EXPECT_THAT([&] { CadModel::read(file); },
                ThrowsMessage<InputError>(AllOf(StartsWith(file.string() + ":"),
                                                HasSubstr(": the STEP file is damaged: entity #5 is defined a second "
                                                          "time (first on line 11)"))))
        << repeat;
  }
}

}  // namespace
}  // namespace hotmesh::geometry
