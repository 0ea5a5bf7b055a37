// Tests of reading meshes gmsh 4.8 makes from its own tutorials (Debian's gmsh-doc): tutorial
// t3's volumes (a box, its extrusion and its twisted extrusion, in the unnamed Physical Volume
// 101) with their combined boundary as one physical surface. gmsh writes the surfaces that
// CombinedBoundary gives reversed with the negative group tag (-103) in $Entities, and reads
// them back as group 103; hotmesh reads them the same way, and names the unnamed groups by
// their tags.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "hotmesh/io/gmsh.hpp"
#include "hotmesh/mesh/validate.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

using mesh::Mesh;
using test::TempDir;

const std::filesystem::path kTutorials = "/usr/share/doc/gmsh-doc/doc/gmsh/tutorial";

/// t3.geo (and t1.geo, which it includes) from gmsh-doc into `dir`, with the boundary of its
/// three volumes as physical surface 103, as `Physical Surface(103) = CombinedBoundary{...}`.
std::filesystem::path tutorial_t3(const TempDir& dir) {
  for (const char* name : {"t1.geo", "t3.geo"}) {
    const auto zipped = kTutorials / (std::string(name) + ".gz");
    EXPECT_TRUE(std::filesystem::exists(zipped)) << zipped << ": gmsh-doc is a test dependency (scripts/install-deps.sh)";
    const auto r = test::run_command("gzip -dc " + test::shell_quote(zipped.string()) + " > " +
                                     test::shell_quote((dir / name).string()));
    EXPECT_EQ(r.exit_code, 0) << r.output;
  }
  const auto geo = dir / "t3.geo";
  test::write_text(geo, test::read_text(geo) + "\nPhysical Surface(103) = CombinedBoundary{ Volume{1, 2, out[1]}; };\n");
  return geo;
}

Mesh mesh_t3(const TempDir& dir, const std::string& format, bool binary) {
  const auto out = dir / ("t3-" + format + (binary ? "-bin" : "") + ".msh");
  const auto r = test::run_command("cd " + test::shell_quote(dir.path().string()) + " && gmsh -3 -nt 1 t3.geo -format " +
                                   format + (binary ? " -bin" : "") + " -o " + test::shell_quote(out.string()));
  EXPECT_EQ(r.exit_code, 0) << "gmsh is a test dependency (scripts/install-deps.sh):\n" << r.output;
  return read_gmsh(out);
}

const mesh::Patch* patch_named(const Mesh& mesh, const std::string& name) {
  const auto it = std::find_if(mesh.patches.begin(), mesh.patches.end(), [&](const auto& p) { return p.name == name; });
  return it == mesh.patches.end() ? nullptr : &*it;
}

/// The faces of a patch as sorted node lists.
std::set<std::vector<mesh::NodeId>> faces_of(const mesh::Patch& patch) {
  std::set<std::vector<mesh::NodeId>> faces;
  for (std::size_t f = 0; f < patch.faces.size(); ++f) {
    std::vector<mesh::NodeId> nodes(patch.faces.nodes(f).begin(), patch.faces.nodes(f).end());
    std::sort(nodes.begin(), nodes.end());
    faces.insert(nodes);
  }
  return faces;
}

TEST(GmshTutorials, SignedPhysicalTagsOfTutorialT3AreTheirGroups) {
  const TempDir dir;
  tutorial_t3(dir);
  Mesh ascii = mesh_t3(dir, "msh41", false);
  // the file holds what the issue showed: the reversed surfaces' group as -103
  EXPECT_THAT(test::read_text(dir / "t3-msh41.msh"), ::testing::HasSubstr(" -103 "));

  const mesh::ValidationReport report = mesh::validate_mesh(ascii);  // every boundary face in a patch
  ASSERT_EQ(ascii.cell_groups.size(), 1u);
  EXPECT_EQ(ascii.cell_groups[0].name, "101");  // Physical Volume(101), unnamed
  EXPECT_EQ(ascii.cell_groups[0].cells.size(), ascii.cells.size());
  ASSERT_EQ(ascii.patches.size(), 2u);
  const mesh::Patch* boundary = patch_named(ascii, "103");
  const mesh::Patch* named = patch_named(ascii, "My surface");  // t1's Physical Surface("My surface")
  ASSERT_NE(boundary, nullptr);
  ASSERT_NE(named, nullptr);
  EXPECT_EQ(boundary->tag, 103);
  // the combined boundary is the whole boundary, each face once, whatever its orientation
  EXPECT_EQ(boundary->faces.size(), report.boundary_faces);
  EXPECT_EQ(faces_of(*boundary).size(), report.boundary_faces);
  const auto all = faces_of(*boundary);
  const auto mine = faces_of(*named);
  EXPECT_FALSE(mine.empty());
  EXPECT_TRUE(std::includes(all.begin(), all.end(), mine.begin(), mine.end()));

  // binary 4.1 (32-bit physical tags) and 2.2 (which gmsh writes with the positive tag) agree
  for (const auto& [format, binary] : {std::pair{"msh41", true}, std::pair{"msh22", false}}) {
    const Mesh other = mesh_t3(dir, format, binary);
    ASSERT_EQ(other.patches.size(), 2u) << format;
    const mesh::Patch* other_boundary = patch_named(other, "103");
    ASSERT_NE(other_boundary, nullptr) << format;
    EXPECT_EQ(faces_of(*other_boundary), all) << format << (binary ? " binary" : "");
    EXPECT_EQ(other.cell_groups.at(0).name, "101");
  }
}

}  // namespace
}  // namespace hotmesh::io
