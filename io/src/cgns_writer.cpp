// hotmesh io: a mesh written as a new CGNS file (hotmesh convert): one base, one
// unstructured zone "Zone", the cells in section "Cells" (QUAD_4 / HEXA_8), then per patch a
// boundary section (BAR_2 / QUAD_4) and a BC (BCGeneral, a PointRange over the section's
// elements at EdgeCenter / FaceCenter), both named as the patch. 2D meshes get physical
// dimension 2 when they lie in z = 0, else 3.
#include <fmt/format.h>

#include <algorithm>

#include "cgns_library.hpp"
#include "hotmesh/geometry/input_error.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/cgns.hpp"

namespace hotmesh::io::cgns {
namespace {

void check_writable(const std::string& file, const mesh::Mesh& mesh) {
  const auto cell = mesh.dimension == 2 ? mesh::ElementType::quad4 : mesh::ElementType::hex8;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    if (mesh.cells.type(c) != cell) {
      throw InputError::in(file, fmt::format("cell {} is a {}: hotmesh writes CGNS files of {} cells only",
                                             mesh.cell_id(static_cast<mesh::CellId>(c)), mesh::name(mesh.cells.type(c)),
                                             mesh::name(cell)));
    }
  }
  for (const mesh::Patch& p : mesh.patches) {
    if (p.name.empty() || p.name.size() > 32 || p.name.find('/') != std::string::npos) {
      throw InputError::in(file, fmt::format("patch '{}': a CGNS name has 1 to 32 characters and no '/'", p.name));
    }
    for (const auto t : p.faces.types()) {
      if (mesh::dimension(t) != mesh.dimension - 1 || t == mesh::ElementType::tri3) {
        throw InputError::in(file, fmt::format("patch '{}' has a {} face: hotmesh writes CGNS faces of quad and hex "
                                               "cells only",
                                               p.name, mesh::name(t)));
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

/// Writes `elements` as a section from element number `first`; returns the number after it.
cgsize_t write_section(const File& file, int base, int zone, const std::string& name, CGNS_ENUMT(ElementType_t) type,
                       const mesh::ElementList& elements, cgsize_t first) {
  std::vector<cgsize_t> nodes;
  nodes.reserve(elements.all_nodes().size());
  for (const mesh::NodeId n : elements.all_nodes()) nodes.push_back(static_cast<cgsize_t>(n) + 1);
  const cgsize_t last = first + static_cast<cgsize_t>(elements.size()) - 1;
  int index = 0;
  file.check(cg_section_write(file.fn(), base, zone, name.c_str(), type, first, last, 0, nodes.data(), &index),
             fmt::format("writing section '{}'", name));
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
  cgsize_t next = cgns::write_section(file, base, zone, "Cells", two_d ? CGNS_ENUMV(QUAD_4) : CGNS_ENUMV(HEXA_8),
                                      mesh.cells, 1);
  for (const mesh::Patch& p : mesh.patches) {
    if (p.faces.empty()) continue;
    const cgsize_t first = next;
    next = cgns::write_section(file, base, zone, p.name, two_d ? CGNS_ENUMV(BAR_2) : CGNS_ENUMV(QUAD_4), p.faces, first);
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
