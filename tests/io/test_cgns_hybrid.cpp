// Tests of CGNS files of hybrid meshes: gmsh's meshes of every cell type (tet4, pyramid5,
// wedge6, hex8 in 3D; tri3 and quad4 in 2D) written by hotmesh (MIXED sections, typed ones for
// one type) and read back with cells, node order, orientation and patches kept; files written
// here with the CGNS library in typed sections per type, BCs by element lists and by vertex
// point lists, two zones of different cell types joined at triangle and quad interfaces, and
// their write-back; higher-order types refused. cgnscheck checks every file hotmesh writes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cgnslib.h>

#include <map>
#include <set>
#include <stdexcept>

#include "read_error.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/cgns.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "hotmesh/mesh/mesh_topology.hpp"
#include "cgns_files.hpp"
#include "hybrid_meshes.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::io {
namespace {

using geometry::Vec3;
using mesh::ElementType;
using ::testing::HasSubstr;

void expect_cgnscheck_accepts(const std::filesystem::path& file) {
  const auto result = test::run_command(std::string(HOTMESH_CGNSCHECK) + " " + test::shell_quote(file.string()));
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_THAT(result.output, ::testing::Not(HasSubstr("ERROR"))) << result.output;
}

/// The type of each section of the file's only zone, by section name.
std::map<std::string, std::string> section_types(const std::filesystem::path& file) {
  std::map<std::string, std::string> types;
  const CgnsSummary summary = describe_cgns(file);
  for (const auto& s : summary.bases.at(0).zones.at(0).sections) types[s.name] = s.type;
  return types;
}

/// Reads `file` and checks it holds exactly the cells (types and node order) and patches of
/// `original`, every cell positively oriented and none reoriented by validation.
void expect_same_mesh(const std::filesystem::path& file, const mesh::Mesh& original) {
  const LoadedMesh back = read_mesh(file);
  EXPECT_EQ(back.mesh.dimension, original.dimension);
  EXPECT_EQ(back.mesh.points, original.points);
  EXPECT_EQ(back.mesh.cells, original.cells);
  EXPECT_EQ(back.validation.reoriented_cells, 0u);
  test::expect_positively_oriented(back.mesh);
  ASSERT_EQ(back.mesh.patches.size(), original.patches.size());
  for (std::size_t p = 0; p < original.patches.size(); ++p) {
    EXPECT_EQ(back.mesh.patches[p].name, original.patches[p].name);
    EXPECT_EQ(back.mesh.patches[p].faces, original.patches[p].faces) << original.patches[p].name;
  }
}

/// hybrid_box.geo read from gmsh: every 3D type, patches of triangles and quads.
mesh::Mesh hybrid_box(const test::TempDir& dir) {
  const mesh::Mesh m = read_mesh(test::hybrid_msh("hybrid_box", 3, dir.path())).mesh;
  const auto counts = test::type_counts(m.cells);
  EXPECT_EQ(counts, (std::map<ElementType, std::size_t>{
                        {ElementType::tet4, 106}, {ElementType::hex8, 16}, {ElementType::wedge6, 28},
                        {ElementType::pyramid5, 4}}));
  for (const char* name : {"bottom", "top", "sides", "xmax"}) {  // xmin: quads only
    const mesh::Patch* p = m.find_patch(name);
    EXPECT_NE(p, nullptr) << name;
    if (!p) continue;
    const auto faces = test::type_counts(p->faces);
    EXPECT_EQ(faces.size(), 2u) << name << " has triangles and quads";
  }
  return m;
}

TEST(CgnsHybrid, EveryCellTypeFromGmshRoundTripsThroughMixedSections) {
  test::TempDir dir;
  const mesh::Mesh m = hybrid_box(dir);
  test::expect_positively_oriented(m);
  write_mesh(dir / "box.cgns", m, m.points);
  expect_cgnscheck_accepts(dir / "box.cgns");
  const auto types = section_types(dir / "box.cgns");
  EXPECT_EQ(types.at("Cells"), "MIXED");
  EXPECT_EQ(types.at("bottom"), "MIXED");  // triangles under the tetrahedra, quads under the hexahedra
  EXPECT_EQ(types.at("xmin"), "QUAD_4");   // hexahedra only at x = 0
  expect_same_mesh(dir / "box.cgns", m);
}

TEST(CgnsHybrid, TrianglesAndQuadsIn2dRoundTrip) {
  test::TempDir dir;
  const mesh::Mesh m = read_mesh(test::hybrid_msh("hybrid_plate", 2, dir.path())).mesh;
  EXPECT_EQ(m.dimension, 2);
  auto counts = test::type_counts(m.cells);
  EXPECT_EQ(counts.size(), 2u);
  EXPECT_EQ(counts[ElementType::quad4], 9u);  // 3 x 3 structured on the left
  EXPECT_GT(counts[ElementType::tri3], 9u);
  write_mesh(dir / "plate.cgns", m, m.points);
  expect_cgnscheck_accepts(dir / "plate.cgns");
  const auto types = section_types(dir / "plate.cgns");
  EXPECT_EQ(types.at("Cells"), "MIXED");
  EXPECT_EQ(types.at("bottom"), "BAR_2");
  EXPECT_EQ(describe_cgns(dir / "plate.cgns").bases.at(0).physical_dimension, 2);
  expect_same_mesh(dir / "plate.cgns", m);
}

TEST(CgnsHybrid, AMeshOfOneTypeGetsTypedSections) {
  test::TempDir dir;
  const mesh::Mesh m = read_mesh(test::hybrid_msh("tet_cube", 3, dir.path())).mesh;
  write_mesh(dir / "tets.cgns", m, m.points);
  expect_cgnscheck_accepts(dir / "tets.cgns");
  const auto types = section_types(dir / "tets.cgns");
  EXPECT_EQ(types.at("Cells"), "TETRA_4");
  EXPECT_EQ(types.at("walls"), "TRI_3");
  expect_same_mesh(dir / "tets.cgns", m);
}

// ---- files written here with the CGNS library ------------------------------------------

void ok(int status) {
  if (status != CG_OK) throw std::runtime_error(std::string("CGNS: ") + cg_get_error());
}

CGNS_ENUMT(ElementType_t) cgns_type(ElementType t) {
  switch (t) {
    case ElementType::tri3: return CGNS_ENUMV(TRI_3);
    case ElementType::quad4: return CGNS_ENUMV(QUAD_4);
    case ElementType::tet4: return CGNS_ENUMV(TETRA_4);
    case ElementType::pyramid5: return CGNS_ENUMV(PYRA_5);
    case ElementType::wedge6: return CGNS_ENUMV(PENTA_6);
    case ElementType::hex8: return CGNS_ENUMV(HEXA_8);
    default: return CGNS_ENUMV(ElementTypeNull);
  }
}

/// One unstructured zone of a 3D base being written: its nodes (a subset of a mesh's, in
/// the mesh's order) and its next element number.
class ZoneWriter {
 public:
  ZoneWriter(int fn, const char* name, const mesh::Mesh& m, const std::vector<std::size_t>& cells) : fn_(fn) {
    local_.assign(m.node_count(), 0);
    for (const std::size_t c : cells) {
      for (const mesh::NodeId n : m.cells.nodes(c)) local_[static_cast<std::size_t>(n)] = 1;
    }
    std::array<std::vector<double>, 3> xyz;
    cgsize_t count = 0;
    for (std::size_t n = 0; n < m.node_count(); ++n) {
      if (!local_[n]) continue;
      local_[n] = ++count;
      xyz[0].push_back(m.points[n].x);
      xyz[1].push_back(m.points[n].y);
      xyz[2].push_back(m.points[n].z);
    }
    std::array<cgsize_t, 3> size{count, static_cast<cgsize_t>(cells.size()), 0};
    ok(cg_zone_write(fn_, 1, name, size.data(), CGNS_ENUMV(Unstructured), &zone_));
    const std::array<const char*, 3> names{"CoordinateX", "CoordinateY", "CoordinateZ"};
    for (std::size_t a = 0; a < 3; ++a) {
      int c = 0;
      ok(cg_coord_write(fn_, 1, zone_, CGNS_ENUMV(RealDouble), names[a], xyz[a].data(), &c));
    }
  }

  /// The node numbers of the zone that are the mesh's `nodes`.
  cgsize_t local(mesh::NodeId n) const { return local_[static_cast<std::size_t>(n)]; }

  /// A section of `elements` (nodes as the mesh's): typed, or MIXED if `mixed`. Returns its
  /// element range.
  std::array<cgsize_t, 2> section(const char* name, const std::vector<std::pair<ElementType, std::vector<mesh::NodeId>>>& elements,
                                  bool mixed) {
    std::vector<cgsize_t> data, offsets{0};
    for (const auto& [type, nodes] : elements) {
      if (mixed) data.push_back(cgns_type(type));
      for (const mesh::NodeId n : nodes) data.push_back(local(n));
      offsets.push_back(static_cast<cgsize_t>(data.size()));
    }
    const std::array<cgsize_t, 2> range{next_, next_ + static_cast<cgsize_t>(elements.size()) - 1};
    int s = 0;
    if (mixed) {
      ok(cg_poly_section_write(fn_, 1, zone_, name, CGNS_ENUMV(MIXED), range[0], range[1], 0, data.data(), offsets.data(), &s));
    } else {
      ok(cg_section_write(fn_, 1, zone_, name, cgns_type(elements.front().first), range[0], range[1], 0, data.data(), &s));
    }
    next_ = range[1] + 1;
    return range;
  }

  void bc_elements(const char* name, CGNS_ENUMT(PointSetType_t) set, const std::vector<cgsize_t>& points) {
    int b = 0;
    ok(cg_boco_write(fn_, 1, zone_, name, CGNS_ENUMV(BCWall), set, static_cast<cgsize_t>(points.size()), points.data(), &b));
    ok(cg_boco_gridlocation_write(fn_, 1, zone_, b, CGNS_ENUMV(FaceCenter)));
  }
  void bc_vertices(const char* name, const std::vector<mesh::NodeId>& nodes) {
    std::vector<cgsize_t> points;
    for (const mesh::NodeId n : nodes) {
      if (local(n) > 0) points.push_back(local(n));
    }
    int b = 0;
    ok(cg_boco_write(fn_, 1, zone_, name, CGNS_ENUMV(BCWall), CGNS_ENUMV(PointList), static_cast<cgsize_t>(points.size()),
                     points.data(), &b));
  }

 private:
  int fn_;
  int zone_ = 0;
  std::vector<cgsize_t> local_;
  cgsize_t next_ = 1;
};

using Elements = std::vector<std::pair<ElementType, std::vector<mesh::NodeId>>>;

Elements of_type(const mesh::ElementList& list, ElementType type, const std::vector<std::size_t>& which) {
  Elements out;
  for (const std::size_t e : which) {
    if (list.type(e) == type) out.emplace_back(type, std::vector<mesh::NodeId>(list.nodes(e).begin(), list.nodes(e).end()));
  }
  return out;
}

std::vector<std::size_t> all(std::size_t n) {
  std::vector<std::size_t> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = i;
  return v;
}

/// The box in one zone: a typed section per cell type (TETRA_4, PYRA_5, PENTA_6, HEXA_8, so
/// the cells come in another order than gmsh's); "bottom" as a TRI_3 and a QUAD_4 section
/// named by one ElementList BC; "sides" as a MIXED section named by an ElementRange BC;
/// "xmax" as TRI_3 and QUAD_4 sections named by no BC (patches "xmax_tri", "xmax_quad");
/// "top" and "xmin" by vertex PointLists.
void write_typed_box(const std::filesystem::path& path, const mesh::Mesh& m) {
  int fn = 0, base = 0;
  ok(cg_set_file_type(CG_FILE_HDF5));
  ok(cg_open(path.c_str(), CG_MODE_WRITE, &fn));
  ok(cg_base_write(fn, "Base", 3, 3, &base));
  {
    ZoneWriter z(fn, "Fluid", m, all(m.cell_count()));
    const auto cells = all(m.cell_count());
    z.section("Tets", of_type(m.cells, ElementType::tet4, cells), false);
    z.section("Pyramids", of_type(m.cells, ElementType::pyramid5, cells), false);
    z.section("Prisms", of_type(m.cells, ElementType::wedge6, cells), false);
    z.section("Hexes", of_type(m.cells, ElementType::hex8, cells), false);
    const auto& bottom = m.find_patch("bottom")->faces;
    const auto tri = z.section("BottomTri", of_type(bottom, ElementType::tri3, all(bottom.size())), false);
    const auto quad = z.section("BottomQuad", of_type(bottom, ElementType::quad4, all(bottom.size())), false);
    std::vector<cgsize_t> list;
    for (cgsize_t e = tri[0]; e <= tri[1]; ++e) list.push_back(e);
    for (cgsize_t e = quad[0]; e <= quad[1]; ++e) list.push_back(e);
    z.bc_elements("bottom", CGNS_ENUMV(PointList), list);  // FaceCenter: element numbers
    const auto& sides = m.find_patch("sides")->faces;
    Elements side_faces;
    for (std::size_t f = 0; f < sides.size(); ++f) {
      side_faces.emplace_back(sides.type(f), std::vector<mesh::NodeId>(sides.nodes(f).begin(), sides.nodes(f).end()));
    }
    const auto range = z.section("Sides", side_faces, true);
    z.bc_elements("sides", CGNS_ENUMV(PointRange), {range[0], range[1]});
    const auto& xmax = m.find_patch("xmax")->faces;
    z.section("xmax_tri", of_type(xmax, ElementType::tri3, all(xmax.size())), false);
    z.section("xmax_quad", of_type(xmax, ElementType::quad4, all(xmax.size())), false);
    z.bc_vertices("top", m.find_patch("top")->nodes);
    z.bc_vertices("xmin", m.find_patch("xmin")->nodes);
  }
  ok(cg_close(fn));
}

/// The patches of a mesh as node sets of their faces, by name.
std::map<std::string, std::vector<test::ElementShape>> patch_faces(const mesh::Mesh& m) {
  std::map<std::string, std::vector<test::ElementShape>> out;
  for (const mesh::Patch& p : m.patches) out[p.name] = test::element_node_sets(p.faces, m.points);
  return out;
}

TEST(CgnsHybrid, TypedSectionsPerTypeAndBcsByElementsAndByVerticesRead) {
  test::TempDir dir;
  const mesh::Mesh m = hybrid_box(dir);
  write_typed_box(dir / "typed.cgns", m);
  const LoadedMesh loaded = read_mesh(dir / "typed.cgns");
  const mesh::Mesh& r = loaded.mesh;
  EXPECT_EQ(r.points, m.points);  // one zone, nodes in the mesh's order
  // The same cells, each with its nodes in the same order, the tetrahedra first.
  EXPECT_EQ(test::element_shapes(r.cells, r.points), test::element_shapes(m.cells, m.points));
  EXPECT_EQ(r.cells.type(0), ElementType::tet4);
  EXPECT_EQ(r.cells.type(r.cell_count() - 1), ElementType::hex8);
  EXPECT_EQ(loaded.validation.reoriented_cells, 0u);
  test::expect_positively_oriented(r);
  // Patches: bottom and sides by elements, top and xmin found from their vertices (the
  // boundary faces, triangles and quads, with all nodes in the list), xmax from the sections.
  auto expected = patch_faces(m);
  const mesh::Patch* xmax = m.find_patch("xmax");
  mesh::ElementList tri, quad;
  for (std::size_t f = 0; f < xmax->faces.size(); ++f) (xmax->faces.type(f) == ElementType::tri3 ? tri : quad).add(xmax->faces.type(f), xmax->faces.nodes(f));
  expected.erase("xmax");
  expected["xmax_tri"] = test::element_node_sets(tri, m.points);
  expected["xmax_quad"] = test::element_node_sets(quad, m.points);
  EXPECT_EQ(patch_faces(r), expected);
  EXPECT_EQ(test::type_counts(r.find_patch("top")->faces), test::type_counts(m.find_patch("top")->faces));
}

/// The box in two zones without connectivity records: "Layers" (hexahedra and prisms) and
/// "Core" (tetrahedra and pyramids), meeting in triangles (prisms on tetrahedra at z = 1)
/// and quads (pyramids against hexahedra at x = 1). Each zone has a MIXED cell section and,
/// per patch, a MIXED section of its faces with an ElementRange BC named as the patch.
void write_two_zone_box(const std::filesystem::path& path, const mesh::Mesh& m) {
  int fn = 0, base = 0;
  ok(cg_set_file_type(CG_FILE_HDF5));
  ok(cg_open(path.c_str(), CG_MODE_WRITE, &fn));
  ok(cg_base_write(fn, "Base", 3, 3, &base));
  const mesh::FaceIndex index(m.cells, m.node_count());
  for (const bool layers : {true, false}) {
    std::vector<std::size_t> cells;
    for (std::size_t c = 0; c < m.cell_count(); ++c) {
      const bool in_layers = m.cells.type(c) == ElementType::hex8 || m.cells.type(c) == ElementType::wedge6;
      if (in_layers == layers) cells.push_back(c);
    }
    ZoneWriter z(fn, layers ? "Layers" : "Core", m, cells);
    Elements volume;
    for (const std::size_t c : cells) volume.emplace_back(m.cells.type(c), std::vector<mesh::NodeId>(m.cells.nodes(c).begin(), m.cells.nodes(c).end()));
    z.section("Cells", volume, true);
    for (const mesh::Patch& p : m.patches) {
      Elements faces;
      for (std::size_t f = 0; f < p.faces.size(); ++f) {
        const auto owner = index.find(p.faces.nodes(f)).at(0).cell;
        if (std::find(cells.begin(), cells.end(), static_cast<std::size_t>(owner)) == cells.end()) continue;
        faces.emplace_back(p.faces.type(f), std::vector<mesh::NodeId>(p.faces.nodes(f).begin(), p.faces.nodes(f).end()));
      }
      if (faces.empty()) continue;
      const auto range = z.section((p.name + "Faces").c_str(), faces, true);
      z.bc_elements(p.name.c_str(), CGNS_ENUMV(PointRange), {range[0], range[1]});
    }
  }
  ok(cg_close(fn));
}

TEST(CgnsHybrid, ZonesOfDifferentCellTypesJoinAtTriangleAndQuadInterfaces) {
  test::TempDir dir;
  const mesh::Mesh m = hybrid_box(dir);
  write_two_zone_box(dir / "zones.cgns", m);
  const LoadedMesh loaded = read_mesh(dir / "zones.cgns");  // validation: no interface face left on the boundary
  const mesh::Mesh& r = loaded.mesh;
  EXPECT_EQ(r.node_count(), m.node_count());
  EXPECT_EQ(loaded.validation.boundary_faces, 114u);
  EXPECT_EQ(test::element_shapes(r.cells, r.points), test::element_shapes(m.cells, m.points));
  test::expect_positively_oriented(r);
  EXPECT_EQ(patch_faces(r), patch_faces(m));
}

TEST(CgnsHybrid, WriteBackOfAHybridTwoZoneFileMovesSharedNodesAsOne) {
  test::TempDir dir;
  const mesh::Mesh m = hybrid_box(dir);
  write_two_zone_box(dir / "zones.cgns", m);
  const LoadedMesh loaded = read_mesh(dir / "zones.cgns");
  std::vector<Vec3> moved;
  for (const Vec3& p : loaded.mesh.points) moved.push_back({p.x + 0.05 * p.z * p.y, p.y, p.z + 0.02 * p.x});
  std::filesystem::create_directories(dir / "out");
  const auto written = loaded.write_back->write(dir / "out", moved, {});
  ASSERT_EQ(written.size(), 1u);
  expect_cgnscheck_accepts(written[0]);
  const auto before = describe_cgns(dir / "zones.cgns"), after = describe_cgns(written[0]);
  ASSERT_EQ(after.bases.at(0).zones.size(), 2u);
  for (std::size_t z = 0; z < 2; ++z) {
    EXPECT_EQ(after.bases[0].zones[z].size, before.bases[0].zones[z].size);
    EXPECT_EQ(after.bases[0].zones[z].sections.size(), before.bases[0].zones[z].sections.size());
  }
  const LoadedMesh again = read_mesh(written[0]);
  EXPECT_EQ(again.mesh.cells, loaded.mesh.cells);
  EXPECT_EQ(again.mesh.patches, loaded.mesh.patches);
  ASSERT_EQ(again.mesh.node_count(), moved.size());
  for (std::size_t n = 0; n < moved.size(); ++n) EXPECT_EQ(again.mesh.points[n], moved[n]) << n;
}

// ---- refused ------------------------------------------------------------------------------

using test_io::read_error;

/// A 3D zone "Fluid" of one quadratic tetrahedron (10 nodes), in a typed TETRA_10 section or
/// in a MIXED section after a TETRA_4.
void write_quadratic_tet(const std::filesystem::path& path, bool mixed) {
  int fn = 0, base = 0, zone = 0, s = 0;
  ok(cg_set_file_type(CG_FILE_HDF5));
  ok(cg_open(path.c_str(), CG_MODE_WRITE, &fn));
  ok(cg_base_write(fn, "Base", 3, 3, &base));
  std::array<cgsize_t, 3> size{10, mixed ? 2 : 1, 0};
  ok(cg_zone_write(fn, base, "Fluid", size.data(), CGNS_ENUMV(Unstructured), &zone));
  const std::vector<double> x{0, 1, 0, 0, 0.5, 0.5, 0, 0, 0.5, 0}, y{0, 0, 1, 0, 0, 0.5, 0.5, 0, 0, 0.5},
      zc{0, 0, 0, 1, 0, 0, 0, 0.5, 0.5, 0.5};
  int c = 0;
  ok(cg_coord_write(fn, base, zone, CGNS_ENUMV(RealDouble), "CoordinateX", x.data(), &c));
  ok(cg_coord_write(fn, base, zone, CGNS_ENUMV(RealDouble), "CoordinateY", y.data(), &c));
  ok(cg_coord_write(fn, base, zone, CGNS_ENUMV(RealDouble), "CoordinateZ", zc.data(), &c));
  if (mixed) {
    const std::vector<cgsize_t> data{CGNS_ENUMV(TETRA_4), 1, 2, 3, 4, CGNS_ENUMV(TETRA_10), 1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
    const std::vector<cgsize_t> offsets{0, 5, 16};
    ok(cg_poly_section_write(fn, base, zone, "Mixed", CGNS_ENUMV(MIXED), 1, 2, 0, data.data(), offsets.data(), &s));
  } else {
    const std::vector<cgsize_t> data{1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
    ok(cg_section_write(fn, base, zone, "Tets", CGNS_ENUMV(TETRA_10), 1, 1, 0, data.data(), &s));
  }
  ok(cg_close(fn));
}

TEST(CgnsHybrid, HigherOrderCellsAreRefusedNamingZoneSectionAndType) {
  test::TempDir dir;
  write_quadratic_tet(dir / "typed.cgns", false);
  EXPECT_THAT(read_error(dir / "typed.cgns"),
              ::testing::AllOf(HasSubstr((dir / "typed.cgns").string()),
                               HasSubstr("zone 'Fluid' section 'Tets' holds 1 TETRA_10 elements"),
                               HasSubstr("TETRA_4, PYRA_5, PENTA_6 and HEXA_8 cells")));
  write_quadratic_tet(dir / "mixed.cgns", true);
  EXPECT_THAT(read_error(dir / "mixed.cgns"),
              HasSubstr("zone 'Fluid' MIXED section 'Mixed': element 2 has type TETRA_10, which hotmesh does not read"));
}

TEST(CgnsHybrid, VolumeCellsInA2dBaseAreRefused) {
  test::TempDir dir;
  int fn = 0, base = 0, zone = 0, s = 0, c = 0;
  ok(cg_set_file_type(CG_FILE_HDF5));
  ok(cg_open((dir / "flat.cgns").c_str(), CG_MODE_WRITE, &fn));
  ok(cg_base_write(fn, "Base", 2, 3, &base));
  std::array<cgsize_t, 3> size{4, 1, 0};
  ok(cg_zone_write(fn, base, "Fluid", size.data(), CGNS_ENUMV(Unstructured), &zone));
  const std::vector<double> x{0, 1, 0, 0}, y{0, 0, 1, 0}, z{0, 0, 0, 1};
  ok(cg_coord_write(fn, base, zone, CGNS_ENUMV(RealDouble), "CoordinateX", x.data(), &c));
  ok(cg_coord_write(fn, base, zone, CGNS_ENUMV(RealDouble), "CoordinateY", y.data(), &c));
  ok(cg_coord_write(fn, base, zone, CGNS_ENUMV(RealDouble), "CoordinateZ", z.data(), &c));
  const std::vector<cgsize_t> data{1, 2, 3, 4};
  ok(cg_section_write(fn, base, zone, "Tets", CGNS_ENUMV(TETRA_4), 1, 1, 0, data.data(), &s));
  ok(cg_close(fn));
  EXPECT_THAT(read_error(dir / "flat.cgns"),
              HasSubstr("zone 'Fluid' section 'Tets' holds 1 TETRA_4 elements: hotmesh reads TRI_3 and QUAD_4 cells"));
}

}  // namespace
}  // namespace hotmesh::io
