// hotmesh io (private): names of the Gmsh element types hotmesh does not read, for messages.
#include "gmsh/gmsh_format.hpp"

#include <string_view>

namespace hotmesh::io::gmsh {
namespace {

struct KnownType {
  int number;
  std::string_view name;
  bool higher_order;  ///< true: the linear version of the shape would be accepted
};

// Gmsh's own numbering (GmshDefines.h, MSH_*); the common higher-order and special types.
constexpr KnownType kKnownTypes[] = {
    {8, "second-order line", true},
    {9, "second-order triangle", true},
    {10, "second-order quadrangle", true},
    {11, "second-order tetrahedron", true},
    {12, "second-order hexahedron", true},
    {13, "second-order prism", true},
    {14, "second-order pyramid", true},
    {16, "8-node second-order quadrangle", true},
    {17, "20-node second-order hexahedron", true},
    {18, "15-node second-order prism", true},
    {19, "13-node second-order pyramid", true},
    {20, "9-node third-order triangle", true},
    {21, "third-order triangle", true},
    {22, "12-node fourth-order triangle", true},
    {23, "fourth-order triangle", true},
    {24, "15-node fifth-order triangle", true},
    {25, "fifth-order triangle", true},
    {26, "third-order line", true},
    {27, "fourth-order line", true},
    {28, "fifth-order line", true},
    {29, "third-order tetrahedron", true},
    {30, "fourth-order tetrahedron", true},
    {31, "fifth-order tetrahedron", true},
    {34, "polygon", false},
    {35, "polyhedron", false},
    {36, "third-order quadrangle", true},
    {37, "fourth-order quadrangle", true},
    {38, "fifth-order quadrangle", true},
    {92, "third-order hexahedron", true},
    {93, "fourth-order hexahedron", true},
};

}  // namespace

std::string unsupported_type_message(int gmsh) {
  for (const KnownType& known : kKnownTypes) {
    if (known.number != gmsh) continue;
    std::string text(known.name);
    text += " (type " + std::to_string(gmsh) + ") is not supported: ";
    text += known.higher_order ? "hotmesh needs linear elements (mesh with Mesh.ElementOrder = 1)"
                               : "hotmesh reads lines, triangles, quadrangles, tetrahedra, hexahedra, prisms "
                                 "and pyramids";
    return text;
  }
  return "unknown element type " + std::to_string(gmsh);
}

}  // namespace hotmesh::io::gmsh
