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

#include <algorithm>
#include <optional>
#include <unordered_map>

#include "cgns/cgns_reader.hpp"
#include "hotmesh/core/input_error.hpp"

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
  int index = 0;                        ///< the section's number in the zone
  std::array<cgsize_t, 2> range{};      ///< its ElementRange
  std::vector<cgsize_t> offsets;        ///< MIXED: its ElementStartOffset
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
    index = s;
    range = {start, end};
    faces.sections.push_back({section, false});
    others.clear();
    skipped = 0;
    if (start < 1 || end < start) {
      throw InputError::in(file.name(), fmt::format("zone '{}' section '{}': its ElementRange {}..{} is {}", zone.name,
                                                    section, start, end,
                                                    end < start ? "reversed (the last element before the first)"
                                                                : "not of element numbers (they start at 1)"));
    }
    const std::int64_t count = std::int64_t{end} - start + 1;
    int npe = 0;
    if (type != CGNS_ENUMV(MIXED) && (cg_npe(type, &npe) != CG_OK || npe <= 0 || npe > 8)) {
      others[cg_ElementTypeName(type)] += static_cast<std::size_t>(count);  // refused unread: NGON_n, TETRA_10, ...
      unsupported();
    }
    const std::vector<cgsize_t> data = connectivity(count, npe);
    if (type == CGNS_ENUMV(MIXED)) {
      read_mixed(data, start);
    } else {
      for (std::int64_t k = 0; k < count; ++k) add(type, static_cast<cgsize_t>(start + k), data.data() + k * npe, npe);
    }
    if (!others.empty()) unsupported();
    if (skipped > 0) {
      spdlog::warn("{}: zone '{}' section '{}': {} elements of lower dimension (NODE, BAR_2) skipped", file.name(),
                   zone.name, section, skipped);
    }
  }

  /// "zone 'Z' section 'S': its ElementRange a..b (n elements)"
  std::string range_text(std::int64_t count) const {
    return fmt::format("zone '{}' section '{}': its ElementRange {}..{} ({} elements)", zone.name, section, range[0],
                       range[1], count);
  }

  /// The section's ElementConnectivity (and for a MIXED section its ElementStartOffset,
  /// checked against it), after checking that the file stores what `count` elements of
  /// `npe` nodes (0: MIXED) take, before any buffer is sized.
  std::vector<cgsize_t> connectivity(std::int64_t count, int npe) {
    double zone_id = 0;
    file.check(cg_zone_id(file.fn(), raw.base, zone.index, &zone_id), fmt::format("zone '{}': finding its node", zone.name));
    cgsize_t size = 0;
    file.check(cg_ElementDataSize(file.fn(), raw.base, zone.index, index, &size),
               fmt::format("zone '{}' section '{}': reading its size", zone.name, section));
    const std::optional<StoredArray> stored = stored_array(file, zone_id, section + "/ElementConnectivity");
    if (!stored || stored->values() != size || size < 0) {
      throw InputError::in(file.name(), fmt::format("zone '{}' section '{}': its ElementConnectivity stores {} values, "
                                                    "not a list of {}",
                                                    zone.name, section, stored ? stored->shape() : "no", size));
    }
    if (npe > 0 && count * npe != size) {
      throw InputError::in(file.name(), fmt::format("{} of {} nodes each need {} values, but its ElementConnectivity "
                                                    "stores {} values",
                                                    range_text(count), npe, count * npe, size));
    }
    std::vector<cgsize_t> data;
    if (npe > 0) {
      data.resize(static_cast<std::size_t>(size));
      file.check(cg_elements_read(file.fn(), raw.base, zone.index, index, data.data(), nullptr),
                 fmt::format("zone '{}' section '{}': reading its elements", zone.name, section));
      return data;
    }
    // MIXED: the library writes the whole stored ElementStartOffset into the offsets' buffer
    // (a file of CGNS before 3.4 has none: the library makes it from ElementRange).
    if (const auto stored_offsets = stored_array(file, zone_id, section + "/ElementStartOffset")) {
      if (stored_offsets->values() != count + 1 || stored_offsets->dimensions.size() != 1) {
        throw InputError::in(file.name(), fmt::format("{} does not match the {} offsets its ElementStartOffset stores "
                                                      "(one per element, and one for the end)",
                                                      range_text(count), stored_offsets->shape()));
      }
    } else if (count > size / 2) {
      throw InputError::in(file.name(), fmt::format("{} need at least {} values (a type and a node each), but its "
                                                    "ElementConnectivity stores {}",
                                                    range_text(count), 2 * count, size));
    }
    data.resize(static_cast<std::size_t>(size));
    offsets.resize(static_cast<std::size_t>(count) + 1);
    file.check(cg_poly_elements_read(file.fn(), raw.base, zone.index, index, data.data(), offsets.data(), nullptr),
               fmt::format("zone '{}' section '{}': reading its elements", zone.name, section));
    if (offsets.front() != 0 || offsets.back() != size) {
      throw InputError::in(file.name(), fmt::format("zone '{}' section '{}': its ElementStartOffset starts at {} and "
                                                    "ends at {}, but its ElementConnectivity stores {} values (from 0 "
                                                    "to {})",
                                                    zone.name, section, offsets.front(), offsets.back(), size, size));
    }
    return data;
  }

  /// The elements of a MIXED section, each a type code and its nodes, where its
  /// ElementStartOffset says (connectivity() checked that the offsets run from 0 to the end).
  void read_mixed(const std::vector<cgsize_t>& data, cgsize_t start) {
    std::size_t at = 0;
    for (std::size_t k = 0; k + 1 < offsets.size(); ++k) {
      const auto e = static_cast<cgsize_t>(start + static_cast<cgsize_t>(k));
      // The code as stored, made an ElementType_t only once it is one (an enum holds no other).
      const cgsize_t code = at < data.size() ? data[at] : 0;
      const auto type = code > 0 && code < NofValidElementTypes ? static_cast<CGNS_ENUMT(ElementType_t)>(code)
                                                                 : CGNS_ENUMV(ElementTypeNull);
      int npe = 0;
      if (type == CGNS_ENUMV(ElementTypeNull) || cg_npe(type, &npe) != CG_OK || npe <= 0 || npe > 8) {
        const std::string name = type == CGNS_ENUMV(ElementTypeNull) ? fmt::format("code {}", code)
                                                                      : std::string(cg_ElementTypeName(type));
        throw InputError::in(file.name(), fmt::format("zone '{}' MIXED section '{}': element {} has type {}, which "
                                                      "hotmesh does not read (it reads {} cells and {} boundary faces "
                                                      "in a {}D base)",
                                                      zone.name, section, e, name,
                                                      cell_names(raw.dimension), face_names(raw.dimension),
                                                      raw.dimension));
      }
      const std::size_t next = at + 1 + static_cast<std::size_t>(npe);
      if (static_cast<std::int64_t>(next) != offsets[k + 1]) {
        throw InputError::in(file.name(), fmt::format("zone '{}' MIXED section '{}': element {} ({}, {} nodes) ends at "
                                                      "value {}, but its ElementStartOffset says {}",
                                                      zone.name, section, e, cg_ElementTypeName(type), npe, next,
                                                      offsets[k + 1]));
      }
      add(type, e, data.data() + at + 1, npe);
      at = next;
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

/// The element numbers a BC by elements names: its list, or its range expanded, once checked
/// to hold no more elements than the zone's boundary sections (each must be one of them).
std::vector<cgsize_t> element_numbers(const File& file, const ZoneFaces& faces, const BcPoints& bc) {
  if (bc.set != CGNS_ENUMV(PointRange) && bc.set != CGNS_ENUMV(ElementRange)) return bc.data;
  const cgsize_t lo = std::min(bc.data[0], bc.data[1]), hi = std::max(bc.data[0], bc.data[1]);
  const std::int64_t count = std::int64_t{hi} - lo + 1;
  if (count > static_cast<std::int64_t>(faces.faces.size())) {
    throw InputError::in(file.name(), fmt::format("{}: its {} {}..{} names {} elements, but the zone's boundary face "
                                                  "sections hold {}",
                                                  bc.where, cg_PointSetTypeName(bc.set), bc.data[0], bc.data[1], count,
                                                  faces.faces.size()));
  }
  std::vector<cgsize_t> elements;
  for (std::int64_t e = lo; e <= hi; ++e) elements.push_back(static_cast<cgsize_t>(e));  // hi may be INT_MAX
  return elements;
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
  if (by_elements(points.set, points.location)) {
    faces_of_elements(file, raw.dimension, faces, element_numbers(file, faces, points), bc);
  } else {
    const std::vector<cgsize_t> entries = expand_point_set(raw, points.set, points.data, 1, node_limits(zone), bc.where);
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
