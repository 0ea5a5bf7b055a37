// Tests of CAD files that crashed hotmesh while it was fuzzed (fuzz/fuzz_cad.cpp,
// docs/fuzzing.md): mutations of the real I-DEAS and CATIA cones of tests/data/cad, kept in
// tests/data/fuzz/. Each made OpenCASCADE follow a null pointer (a segmentation fault, exit
// 139) before the readers turned its faults into errors (issue 18, item 3); now each is read,
// or refused as a user error naming the file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/geometry/input_error.hpp"
#include "test_support.hpp"

namespace hotmesh::geometry {
namespace {

using ::testing::HasSubstr;
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

}  // namespace
}  // namespace hotmesh::geometry
