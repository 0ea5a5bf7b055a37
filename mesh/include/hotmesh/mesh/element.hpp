// hotmesh mesh: linear element types and their reference topology.
// Node numbering is Gmsh's, which for these linear elements is also VTK's:
//   quad4: 0-1-2-3 counter-clockwise in the x-y plane
//   hex8:  0-1-2-3 bottom face, 4-5-6-7 top face above them (right-handed)
//   tet4:  0-1-2 base, 3 on the side the base's right-hand normal points to
//   wedge6: 0-1-2 bottom triangle, 3-4-5 top;  pyramid5: 0-1-2-3 base, 4 apex
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

namespace hotmesh::mesh {

enum class ElementType : std::uint8_t { line2, tri3, quad4, tet4, hex8, wedge6, pyramid5 };

inline constexpr int kMaxElementNodes = 8;
inline constexpr int kMaxElementFaces = 6;
inline constexpr int kMaxFaceNodes = 4;

/// Spatial dimension of the element: 1 (line2), 2 (tri3, quad4) or 3.
int dimension(ElementType type);
int node_count(ElementType type);
std::string_view name(ElementType type);

/// One face (3D) or edge (2D) of a cell, its nodes ordered so that the right-hand normal
/// (in 2D: the right side of the directed edge) points out of the cell.
struct LocalFace {
  std::uint8_t count = 0;
  std::array<std::uint8_t, kMaxFaceNodes> nodes{};
};

/// The boundary faces (edges for 2D cells) of a cell type, outward oriented.
std::span<const LocalFace> faces(ElementType type);

/// The element type of a face with `n` nodes of a cell of dimension `cell_dimension`.
ElementType face_type(int cell_dimension, int n);

/// At each corner, the d neighbouring corners whose edge vectors e_1..e_d give a positive
/// determinant det[e_1 .. e_d] for a valid element (the "corner Jacobian").
/// Pyramids use their four base corners only (the apex has four edges).
struct CornerStencil {
  std::uint8_t corner = 0;
  std::array<std::uint8_t, 3> neighbours{};
};
std::span<const CornerStencil> corner_stencils(ElementType type);

/// Scale making the scaled corner Jacobian of the ideal element equal to 1
/// (square, cube, equilateral triangle and prism, regular tetrahedron, pyramid with
/// equilateral sides).
double ideal_corner_scale(ElementType type);

/// A renumbering that mirrors the element in reference space: applied to a cell whose
/// corner Jacobians are all negative it yields the same cell with positive orientation.
std::span<const std::uint8_t> reversal(ElementType type);

}  // namespace hotmesh::mesh
