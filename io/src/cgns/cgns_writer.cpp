// hotmesh io: a mesh written as a new CGNS file (hotmesh convert): one base, one
// unstructured zone "Zone", the cells in section "Cells", then per patch a boundary section
// and a BC (BCGeneral, a PointRange over the section's elements at EdgeCenter / FaceCenter),
// both named as the patch. 2D meshes get physical dimension 2 when they lie in z = 0, else 3.
// Cells: TRI_3, QUAD_4 (2D), TETRA_4, PYRA_5, PENTA_6, HEXA_8 (3D); faces: BAR_2 (2D), TRI_3,
// QUAD_4 (3D). A section of elements of one type is written typed (QUAD_4, HEXA_8, ...), a
// section of several types as one MIXED section: MIXED keeps the mesh's cell (and face)
// order, so the element numbers are the cell numbers and a file read back gives the same
// mesh; sections per type would renumber the cells of a hybrid mesh type by type. The node
// order of every linear type is the same in CGNS and in hotmesh (Gmsh's order).
#include <fmt/format.h>

#include <algorithm>
#include <functional>

#include "cgns/cgns_library.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/cgns.hpp"

namespace hotmesh::io::cgns {
namespace {

/// The CGNS type of a hotmesh element type.
CGNS_ENUMT(ElementType_t) cgns_type(mesh::ElementType type) {
  switch (type) {
    case mesh::ElementType::line2: return CGNS_ENUMV(BAR_2);
    case mesh::ElementType::tri3: return CGNS_ENUMV(TRI_3);
    case mesh::ElementType::quad4: return CGNS_ENUMV(QUAD_4);
    case mesh::ElementType::tet4: return CGNS_ENUMV(TETRA_4);
    case mesh::ElementType::pyramid5: return CGNS_ENUMV(PYRA_5);
    case mesh::ElementType::wedge6: return CGNS_ENUMV(PENTA_6);
    case mesh::ElementType::hex8: return CGNS_ENUMV(HEXA_8);
  }
  return CGNS_ENUMV(ElementTypeNull);
}

void check_writable(const std::string& file, const mesh::Mesh& mesh) {
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    if (mesh::dimension(mesh.cells.type(c)) != mesh.dimension) {
      throw InputError::in(file, fmt::format("cell {} is a {} in a {}D mesh: hotmesh writes CGNS cells of the mesh's "
                                             "dimension only",
                                             mesh.cell_id(static_cast<mesh::CellId>(c)), mesh::name(mesh.cells.type(c)),
                                             mesh.dimension));
    }
  }
  for (const mesh::Patch& p : mesh.patches) {
    if (p.name.empty() || p.name.size() > 32 || p.name.find('/') != std::string::npos) {
      throw InputError::in(file, fmt::format("patch '{}': a CGNS name has 1 to 32 characters and no '/'", p.name));
    }
    for (const auto t : p.faces.types()) {
      if (mesh::dimension(t) != mesh.dimension - 1) {
        throw InputError::in(file, fmt::format("patch '{}' has a {} face: the boundary faces of a {}D mesh are {}",
                                               p.name, mesh::name(t), mesh.dimension,
                                               mesh.dimension == 2 ? "lines" : "triangles and quads"));
      }
    }
  }
}

void write_coordinates(const File& file, int base, int zone, std::span<const geometry::Vec3> points,
                       int physical_dimension) {
  std::vector<double> values(points.size());
  const std::array<const char*, 3> names{"CoordinateX", "CoordinateY", "CoordinateZ"};
  for (int axis = 0; axis < physical_dimension; ++axis) {
    std::transform(points.begin(), points.end(), values.begin(),
                   [axis](const geometry::Vec3& p) { return axis == 0 ? p.x : (axis == 1 ? p.y : p.z); });
    int index = 0;
    file.check(cg_coord_write(file.fn(), base, zone, CGNS_ENUMV(RealDouble), names[static_cast<std::size_t>(axis)],
                              values.data(), &index),
               fmt::format("writing {}", names[static_cast<std::size_t>(axis)]));
  }
}

/// Writes `elements` as a section from element number `first`, typed if they are of one
/// type, else MIXED; returns the number after it.
cgsize_t write_section(const File& file, int base, int zone, const std::string& name, const mesh::ElementList& elements,
                       cgsize_t first) {
  const auto types = elements.types();
  const bool mixed = std::adjacent_find(types.begin(), types.end(), std::not_equal_to<>()) != types.end();
  std::vector<cgsize_t> data, offsets{0};
  data.reserve(elements.all_nodes().size() + (mixed ? elements.size() : 0));
  for (std::size_t e = 0; e < elements.size(); ++e) {
    if (mixed) data.push_back(static_cast<cgsize_t>(cgns_type(elements.type(e))));
    for (const mesh::NodeId n : elements.nodes(e)) data.push_back(static_cast<cgsize_t>(n) + 1);
    offsets.push_back(static_cast<cgsize_t>(data.size()));
  }
  const cgsize_t last = first + static_cast<cgsize_t>(elements.size()) - 1;
  const std::string what = fmt::format("writing section '{}'", name);
  int index = 0;
  if (mixed) {
    file.check(cg_poly_section_write(file.fn(), base, zone, name.c_str(), CGNS_ENUMV(MIXED), first, last, 0, data.data(),
                                     offsets.data(), &index),
               what);
  } else {
    file.check(cg_section_write(file.fn(), base, zone, name.c_str(), cgns_type(types.front()), first, last, 0,
                                data.data(), &index),
               what);
  }
  return last + 1;
}

}  // namespace
}  // namespace hotmesh::io::cgns

namespace hotmesh::io {

void write_cgns(const std::filesystem::path& path, const mesh::Mesh& mesh, std::span<const geometry::Vec3> points) {
  cgns::check_writable(path.string(), mesh);
  AtomicPath out(path);
  cgns::File file(out.temporary(), CG_MODE_WRITE);
  const bool planar = std::all_of(points.begin(), points.end(), [](const geometry::Vec3& p) { return p.z == 0.0; });
  const int physical = mesh.dimension == 2 && planar ? 2 : 3;
  int base = 0, zone = 0;
  file.check(cg_base_write(file.fn(), "Base", mesh.dimension, physical, &base), "writing the base");
  std::array<cgsize_t, 3> size{static_cast<cgsize_t>(points.size()), static_cast<cgsize_t>(mesh.cell_count()), 0};
  file.check(cg_zone_write(file.fn(), base, "Zone", size.data(), CGNS_ENUMV(Unstructured), &zone), "writing the zone");
  cgns::write_coordinates(file, base, zone, points, physical);
  const bool two_d = mesh.dimension == 2;
  cgsize_t next = mesh.cells.empty() ? 1 : cgns::write_section(file, base, zone, "Cells", mesh.cells, 1);
  for (const mesh::Patch& p : mesh.patches) {
    if (p.faces.empty()) continue;
    const cgsize_t first = next;
    next = cgns::write_section(file, base, zone, p.name, p.faces, first);
    const std::array<cgsize_t, 2> range{first, next - 1};
    int bc = 0;
    file.check(cg_boco_write(file.fn(), base, zone, p.name.c_str(), CGNS_ENUMV(BCGeneral), CGNS_ENUMV(PointRange), 2,
                             range.data(), &bc),
               fmt::format("writing BC '{}'", p.name));
    file.check(cg_boco_gridlocation_write(file.fn(), base, zone, bc, two_d ? CGNS_ENUMV(EdgeCenter) : CGNS_ENUMV(FaceCenter)),
               fmt::format("writing the location of BC '{}'", p.name));
  }
  file.close();
  out.commit();
}

}  // namespace hotmesh::io
