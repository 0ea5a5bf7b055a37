// hotmesh io (private): facts about the Gmsh .msh format shared by the reader and the writer:
// the element-type numbers and how they map onto hotmesh's linear element types. Gmsh's node
// order for these linear elements is hotmesh's (see deform/element.hpp), so no permutation.
#pragma once

#include <optional>
#include <string>

#include "hotmesh/mesh/element.hpp"

namespace hotmesh::io::gmsh {

inline constexpr int kPointType = 15;  ///< one-node element; readers skip it

/// Gmsh element-type number of a hotmesh element type.
constexpr int gmsh_type(mesh::ElementType type) {
  switch (type) {
    case mesh::ElementType::line2: return 1;
    case mesh::ElementType::tri3: return 2;
    case mesh::ElementType::quad4: return 3;
    case mesh::ElementType::tet4: return 4;
    case mesh::ElementType::hex8: return 5;
    case mesh::ElementType::wedge6: return 6;
    case mesh::ElementType::pyramid5: return 7;
  }
  return 0;
}

/// The hotmesh type of a supported Gmsh element-type number (1..7), nothing for the rest.
constexpr std::optional<mesh::ElementType> element_type(int gmsh) {
  switch (gmsh) {
    case 1: return mesh::ElementType::line2;
    case 2: return mesh::ElementType::tri3;
    case 3: return mesh::ElementType::quad4;
    case 4: return mesh::ElementType::tet4;
    case 5: return mesh::ElementType::hex8;
    case 6: return mesh::ElementType::wedge6;
    case 7: return mesh::ElementType::pyramid5;
    default: return std::nullopt;
  }
}

/// Why an element type the reader cannot use is rejected: for a Gmsh type that is neither
/// linear (1..7) nor a point (15), a message naming it, e.g. "second-order hexahedron
/// (type 12) is not supported: ...", or "unknown element type 99".
std::string unsupported_type_message(int gmsh);

}  // namespace hotmesh::io::gmsh
