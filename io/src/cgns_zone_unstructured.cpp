// hotmesh io: the sections and boundary conditions of an unstructured CGNS zone.
// Cells: TRI_3 and QUAD_4 (2D bases), TETRA_4, PYRA_5, PENTA_6 and HEXA_8 (3D bases), in
// typed sections or in MIXED ones. Faces: BAR_2 (2D) or TRI_3 and QUAD_4 (3D), typed or
// MIXED, kept by element number for the BCs that name elements; a face section no BC refers
// to becomes a patch of its own, named as the section. Elements of a lower dimension (NODE;
// BAR_2 in 3D: the curves some generators export) are skipped, as the Gmsh reader skips them.
// Higher-order types (TRI_6, TETRA_10, HEXA_27, ...) are refused, naming zone, section, type.
//
// Node order: the CGNS SIDS numbering of the linear elements ("Unstructured Grid Element
// Numbering Conventions") is the same as Gmsh's, which hotmesh uses (mesh/element.hpp), so
// the nodes are taken as they are: TRI_3 / QUAD_4 counter-clockwise; TETRA_4 base N1-N2-N3
// with N4 on the side of its right-hand normal (SIDS face F1 = N1 N3 N2 points out); PYRA_5
// base N1..N4, apex N5 (F1 = N1 N4 N3 N2 out); PENTA_6 triangles N1-N2-N3 and N4-N5-N6
// above them (F4 = N1 N3 N2 out); HEXA_8 N1..N4 bottom, N5..N8 above them.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <optional>
#include <unordered_map>

#include "cgns_reader.hpp"
#include "hotmesh/geometry/input_error.hpp"

namespace hotmesh::io::cgns {
namespace {

/// The element types hotmesh reads as cells / boundary faces in a base of `dimension`.
const char* cell_names(int dimension) {
  return dimension == 2 ? "TRI_3 and QUAD_4" : "TETRA_4, PYRA_5, PENTA_6 and HEXA_8";
}
const char* face_names(int dimension) { return dimension == 2 ? "BAR_2" : "TRI_3 and QUAD_4"; }

/// The faces of one zone's boundary sections, by element number.
struct ZoneFaces {
  mesh::ElementList faces;                   ///< in raw node ids
  std::vector<int> section_of;               ///< by face: index into sections
  std::unordered_map<cgsize_t, std::int32_t> by_element;
  struct Section {
    std::string name;
    bool referenced = false;
  };
  std::vector<Section> sections;
};

struct SectionReader {
  const File& file;
  RawMesh& raw;
  ZoneRecord& zone;
  ZoneFaces& faces;
  std::string section;
  std::unordered_map<std::string, std::size_t> others;  ///< unsupported element types, counted
  std::size_t skipped = 0;                               ///< lower-dimensional elements

  /// The hotmesh cell type of a CGNS element type in this base, if it is a cell.
  std::optional<mesh::ElementType> cell_type(CGNS_ENUMT(ElementType_t) t) const {
    if (raw.dimension == 2) {
      if (t == CGNS_ENUMV(TRI_3)) return mesh::ElementType::tri3;
      if (t == CGNS_ENUMV(QUAD_4)) return mesh::ElementType::quad4;
      return std::nullopt;
    }
    switch (t) {
      case CGNS_ENUMV(TETRA_4): return mesh::ElementType::tet4;
      case CGNS_ENUMV(PYRA_5): return mesh::ElementType::pyramid5;
      case CGNS_ENUMV(PENTA_6): return mesh::ElementType::wedge6;
      case CGNS_ENUMV(HEXA_8): return mesh::ElementType::hex8;
      default: return std::nullopt;
    }
  }
  /// The hotmesh face type of a CGNS element type in this base, if it is a boundary face.
  std::optional<mesh::ElementType> face_type(CGNS_ENUMT(ElementType_t) t) const {
    if (raw.dimension == 2) return t == CGNS_ENUMV(BAR_2) ? std::optional(mesh::ElementType::line2) : std::nullopt;
    if (t == CGNS_ENUMV(TRI_3)) return mesh::ElementType::tri3;
    if (t == CGNS_ENUMV(QUAD_4)) return mesh::ElementType::quad4;
    return std::nullopt;
  }
  bool is_lower(CGNS_ENUMT(ElementType_t) t) const {
    return t == CGNS_ENUMV(NODE) || (raw.dimension == 3 && t == CGNS_ENUMV(BAR_2));
  }

  void add(CGNS_ENUMT(ElementType_t) type, cgsize_t element, const cgsize_t* nodes, int count) {
    std::array<NodeId, 8> ids{};
    for (int i = 0; i < count; ++i) {
      if (nodes[i] < 1 || static_cast<std::size_t>(nodes[i]) > zone.node_count) {
        throw InputError::in(file.name(), fmt::format("zone '{}' section '{}': element {} refers to node {}, but the "
                                                      "zone has {} nodes",
                                                      zone.name, section, element, nodes[i], zone.node_count));
      }
      ids[static_cast<std::size_t>(i)] = zone.first_node + static_cast<NodeId>(nodes[i] - 1);
    }
    const std::span<const NodeId> view(ids.data(), static_cast<std::size_t>(count));
    if (const auto cell = cell_type(type)) {
      raw.cells.add(*cell, view);  // CGNS and Gmsh number linear elements alike (see the top)
    } else if (const auto face = face_type(type)) {
      faces.by_element[element] = static_cast<std::int32_t>(faces.faces.size());
      faces.faces.add(*face, view);
      faces.section_of.push_back(static_cast<int>(faces.sections.size()) - 1);
    } else if (is_lower(type)) {
      ++skipped;
    } else {
      ++others[cg_ElementTypeName(type)];
    }
  }

  void read(int s) {
    Label name{};
    CGNS_ENUMT(ElementType_t) type{};
    cgsize_t start = 0, end = 0;
    int boundary = 0, parent_flag = 0;
    file.check(cg_section_read(file.fn(), raw.base, zone.index, s, name, &type, &start, &end, &boundary, &parent_flag),
               fmt::format("zone '{}': reading section {}", zone.name, s));
    section = name;
    faces.sections.push_back({section, false});
    cgsize_t size = 0;
    file.check(cg_ElementDataSize(file.fn(), raw.base, zone.index, s, &size),
               fmt::format("zone '{}' section '{}': reading its size", zone.name, section));
    std::vector<cgsize_t> data(static_cast<std::size_t>(size));
    const bool variable = type == CGNS_ENUMV(MIXED) || type == CGNS_ENUMV(NGON_n) || type == CGNS_ENUMV(NFACE_n);
    std::vector<cgsize_t> offsets(variable ? static_cast<std::size_t>(end - start + 2) : 0);
    const std::string what = fmt::format("zone '{}' section '{}': reading its elements", zone.name, section);
    if (variable) {
      file.check(cg_poly_elements_read(file.fn(), raw.base, zone.index, s, data.data(), offsets.data(), nullptr), what);
    } else {
      file.check(cg_elements_read(file.fn(), raw.base, zone.index, s, data.data(), nullptr), what);
    }
    others.clear();
    skipped = 0;
    if (type == CGNS_ENUMV(MIXED)) {
      read_mixed(data, start, end);
    } else {
      int npe = 0;
      if (variable || cg_npe(type, &npe) != CG_OK || npe <= 0 || npe > 8) {
        others[cg_ElementTypeName(type)] += static_cast<std::size_t>(end - start + 1);
      } else {
        for (cgsize_t e = start; e <= end; ++e) add(type, e, data.data() + (e - start) * npe, npe);
      }
    }
    if (!others.empty()) unsupported();
    if (skipped > 0) {
      spdlog::warn("{}: zone '{}' section '{}': {} elements of lower dimension (NODE, BAR_2) skipped", file.name(),
                   zone.name, section, skipped);
    }
  }

  void read_mixed(const std::vector<cgsize_t>& data, cgsize_t start, cgsize_t end) {
    std::size_t at = 0;
    for (cgsize_t e = start; e <= end; ++e) {
      const auto type = static_cast<CGNS_ENUMT(ElementType_t)>(data.at(at));
      int npe = 0;
      if (cg_npe(type, &npe) != CG_OK || npe <= 0 || npe > 8 || at + 1 + static_cast<std::size_t>(npe) > data.size()) {
        throw InputError::in(file.name(), fmt::format("zone '{}' MIXED section '{}': element {} has type {}, which "
                                                      "hotmesh does not read (it reads {} cells and {} boundary faces "
                                                      "in a {}D base)",
                                                      zone.name, section, e, cg_ElementTypeName(type),
                                                      cell_names(raw.dimension), face_names(raw.dimension),
                                                      raw.dimension));
      }
      add(type, e, data.data() + at + 1, npe);
      at += 1 + static_cast<std::size_t>(npe);
    }
  }

  [[noreturn]] void unsupported() const {
    std::string list;
    for (const auto& [type, count] : others) list += fmt::format("{}{} {}", list.empty() ? "" : ", ", count, type);
    throw InputError::in(file.name(), fmt::format("zone '{}' section '{}' holds {} elements: hotmesh reads {} cells and "
                                                  "{} boundary faces in a {}D base (linear elements only)",
                                                  zone.name, section, list, cell_names(raw.dimension),
                                                  face_names(raw.dimension), raw.dimension));
  }
};

/// The faces an element-based BC names, from the zone's boundary sections.
void faces_of_elements(const File& file, int file_dimension, ZoneFaces& faces, const std::vector<cgsize_t>& elements,
                       RawBc& bc) {
  for (const cgsize_t e : elements) {
    const auto it = faces.by_element.find(e);
    if (it == faces.by_element.end()) {
      throw InputError::in(file.name(), fmt::format("{} names element {}, which is in no boundary face section ({}) of "
                                                    "the zone",
                                                    bc.where, e, faces.faces.empty() ? "there is none" : face_names(file_dimension)));
    }
    const auto f = static_cast<std::size_t>(it->second);
    bc.faces.add(faces.faces.type(f), faces.faces.nodes(f));
    faces.sections[static_cast<std::size_t>(faces.section_of[f])].referenced = true;
  }
}

bool by_elements(CGNS_ENUMT(PointSetType_t) set, CGNS_ENUMT(GridLocation_t) location) {
  if (set == CGNS_ENUMV(ElementRange) || set == CGNS_ENUMV(ElementList)) return true;
  return location != CGNS_ENUMV(Vertex);
}

void read_bc(const File& file, RawMesh& raw, std::size_t z, ZoneFaces& faces, int b) {
  const ZoneRecord& zone = raw.zones[z];
  const BcPoints points = read_bc_points(file, raw, zone, b);
  RawBc bc;
  bc.where = points.where;
  bc.patch = points.patch;
  bc.zone = z;
  const std::vector<cgsize_t> entries = expand_point_set(points.set, points.data, 1);
  if (by_elements(points.set, points.location)) {
    faces_of_elements(file, raw.dimension, faces, entries, bc);
  } else {
    bc.by_points = true;
    for (const cgsize_t p : entries) {
      if (p < 1 || static_cast<std::size_t>(p) > zone.node_count) {
        throw InputError::in(file.name(), fmt::format("{} names node {}, but the zone has {} nodes", bc.where, p,
                                                      zone.node_count));
      }
      bc.nodes.push_back(zone.first_node + static_cast<NodeId>(p - 1));
    }
  }
  raw.bcs.push_back(std::move(bc));
}

}  // namespace

void read_unstructured_zone(const File& file, RawMesh& raw, std::size_t z) {
  ZoneRecord& zone = raw.zones[z];
  int sections = 0;
  file.check(cg_nsections(file.fn(), raw.base, zone.index, &sections), fmt::format("zone '{}': reading its sections", zone.name));
  ZoneFaces faces;
  SectionReader reader{file, raw, zone, faces, {}, {}};
  for (int s = 1; s <= sections; ++s) reader.read(s);
  int bcs = 0;
  file.check(cg_nbocos(file.fn(), raw.base, zone.index, &bcs), fmt::format("zone '{}': reading its BCs", zone.name));
  for (int b = 1; b <= bcs; ++b) read_bc(file, raw, z, faces, b);
  for (std::size_t s = 0; s < faces.sections.size(); ++s) {
    if (faces.sections[s].referenced) continue;
    RawBc bc;
    bc.patch = faces.sections[s].name;
    bc.where = fmt::format("zone '{}' section '{}'", zone.name, bc.patch);
    bc.zone = z;
    bc.from_section = true;
    for (std::size_t f = 0; f < faces.faces.size(); ++f) {
      if (faces.section_of[f] == static_cast<int>(s)) bc.faces.add(faces.faces.type(f), faces.faces.nodes(f));
    }
    if (!bc.faces.empty()) raw.bcs.push_back(std::move(bc));
  }
}

}  // namespace hotmesh::io::cgns
