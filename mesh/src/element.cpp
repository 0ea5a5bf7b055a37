#include "hotmesh/mesh/element.hpp"

#include <cassert>
#include <cmath>
#include <stdexcept>

namespace hotmesh::mesh {
namespace {

constexpr LocalFace F(std::uint8_t a, std::uint8_t b) { return {2, {a, b, 0, 0}}; }
constexpr LocalFace F(std::uint8_t a, std::uint8_t b, std::uint8_t c) { return {3, {a, b, c, 0}}; }
constexpr LocalFace F(std::uint8_t a, std::uint8_t b, std::uint8_t c, std::uint8_t d) {
  return {4, {a, b, c, d}};
}

constexpr LocalFace kTriFaces[] = {F(0, 1), F(1, 2), F(2, 0)};
constexpr LocalFace kQuadFaces[] = {F(0, 1), F(1, 2), F(2, 3), F(3, 0)};
constexpr LocalFace kTetFaces[] = {F(0, 2, 1), F(0, 1, 3), F(1, 2, 3), F(0, 3, 2)};
constexpr LocalFace kHexFaces[] = {F(0, 3, 2, 1), F(4, 5, 6, 7), F(0, 1, 5, 4),
                                   F(1, 2, 6, 5), F(2, 3, 7, 6), F(3, 0, 4, 7)};
constexpr LocalFace kWedgeFaces[] = {F(0, 2, 1), F(3, 4, 5), F(0, 1, 4, 3), F(1, 2, 5, 4),
                                     F(2, 0, 3, 5)};
constexpr LocalFace kPyramidFaces[] = {F(0, 3, 2, 1), F(0, 1, 4), F(1, 2, 4), F(2, 3, 4),
                                       F(3, 0, 4)};

constexpr CornerStencil kTriCorners[] = {{0, {1, 2, 0}}, {1, {2, 0, 0}}, {2, {0, 1, 0}}};
constexpr CornerStencil kQuadCorners[] = {
    {0, {1, 3, 0}}, {1, {2, 0, 0}}, {2, {3, 1, 0}}, {3, {0, 2, 0}}};
constexpr CornerStencil kTetCorners[] = {
    {0, {1, 2, 3}}, {1, {2, 0, 3}}, {2, {0, 1, 3}}, {3, {0, 2, 1}}};
constexpr CornerStencil kHexCorners[] = {{0, {1, 3, 4}}, {1, {2, 0, 5}}, {2, {3, 1, 6}},
                                         {3, {0, 2, 7}}, {4, {7, 5, 0}}, {5, {4, 6, 1}},
                                         {6, {5, 7, 2}}, {7, {6, 4, 3}}};
constexpr CornerStencil kWedgeCorners[] = {{0, {1, 2, 3}}, {1, {2, 0, 4}}, {2, {0, 1, 5}},
                                           {3, {5, 4, 0}}, {4, {3, 5, 1}}, {5, {4, 3, 2}}};
constexpr CornerStencil kPyramidCorners[] = {
    {0, {1, 3, 4}}, {1, {2, 0, 4}}, {2, {3, 1, 4}}, {3, {0, 2, 4}}};

constexpr std::uint8_t kLineReversal[] = {1, 0};
constexpr std::uint8_t kTriReversal[] = {0, 2, 1};
constexpr std::uint8_t kQuadReversal[] = {0, 3, 2, 1};
constexpr std::uint8_t kTetReversal[] = {0, 2, 1, 3};
constexpr std::uint8_t kHexReversal[] = {4, 5, 6, 7, 0, 1, 2, 3};
constexpr std::uint8_t kWedgeReversal[] = {3, 4, 5, 0, 1, 2};
constexpr std::uint8_t kPyramidReversal[] = {0, 3, 2, 1, 4};

}  // namespace

int dimension(ElementType type) {
  switch (type) {
    case ElementType::line2: return 1;
    case ElementType::tri3:
    case ElementType::quad4: return 2;
    case ElementType::tet4:
    case ElementType::hex8:
    case ElementType::wedge6:
    case ElementType::pyramid5: return 3;
  }
  return 0;
}

int node_count(ElementType type) {
  switch (type) {
    case ElementType::line2: return 2;
    case ElementType::tri3: return 3;
    case ElementType::quad4: return 4;
    case ElementType::tet4: return 4;
    case ElementType::hex8: return 8;
    case ElementType::wedge6: return 6;
    case ElementType::pyramid5: return 5;
  }
  return 0;
}

std::string_view name(ElementType type) {
  switch (type) {
    case ElementType::line2: return "line2";
    case ElementType::tri3: return "tri3";
    case ElementType::quad4: return "quad4";
    case ElementType::tet4: return "tet4";
    case ElementType::hex8: return "hex8";
    case ElementType::wedge6: return "wedge6";
    case ElementType::pyramid5: return "pyramid5";
  }
  return "?";
}

std::span<const LocalFace> faces(ElementType type) {
  switch (type) {
    case ElementType::line2: return {};  // only cells have faces
    case ElementType::tri3: return kTriFaces;
    case ElementType::quad4: return kQuadFaces;
    case ElementType::tet4: return kTetFaces;
    case ElementType::hex8: return kHexFaces;
    case ElementType::wedge6: return kWedgeFaces;
    case ElementType::pyramid5: return kPyramidFaces;
  }
  return {};
}

ElementType face_type(int cell_dimension, int n) {
  if (cell_dimension == 2 && n == 2) return ElementType::line2;
  if (cell_dimension == 3 && n == 3) return ElementType::tri3;
  if (cell_dimension == 3 && n == 4) return ElementType::quad4;
  throw std::logic_error("no face type with that node count");
}

std::span<const CornerStencil> corner_stencils(ElementType type) {
  switch (type) {
    case ElementType::line2: return {};
    case ElementType::tri3: return kTriCorners;
    case ElementType::quad4: return kQuadCorners;
    case ElementType::tet4: return kTetCorners;
    case ElementType::hex8: return kHexCorners;
    case ElementType::wedge6: return kWedgeCorners;
    case ElementType::pyramid5: return kPyramidCorners;
  }
  return {};
}

double ideal_corner_scale(ElementType type) {
  switch (type) {
    case ElementType::tri3:
    case ElementType::wedge6: return 2.0 / std::sqrt(3.0);  // 1 / sin 60°
    case ElementType::tet4:
    case ElementType::pyramid5: return std::sqrt(2.0);
    case ElementType::line2:
    case ElementType::quad4:
    case ElementType::hex8: return 1.0;
  }
  return 1.0;
}

std::span<const std::uint8_t> reversal(ElementType type) {
  switch (type) {
    case ElementType::line2: return kLineReversal;
    case ElementType::tri3: return kTriReversal;
    case ElementType::quad4: return kQuadReversal;
    case ElementType::tet4: return kTetReversal;
    case ElementType::hex8: return kHexReversal;
    case ElementType::wedge6: return kWedgeReversal;
    case ElementType::pyramid5: return kPyramidReversal;
  }
  return {};
}

}  // namespace hotmesh::mesh
