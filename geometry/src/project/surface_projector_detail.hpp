// hotmesh geometry (internal): what the surface projector's set-up (surface_projector_setup.cpp)
// and its queries (surface_projector.cpp) share: when a normal vanishes, and symmetric 2x2
// matrices.
#pragma once

namespace hotmesh::geometry::detail {

/// A normal |S_u x S_v| below this times the patch's largest |S_u| |S_v| vanishes.
constexpr double kDegenerateNormal = 1e-8;

/// A symmetric 2x2 matrix [uu uv; uv vv].
struct Sym2 {
  double uu;
  double uv;
  double vv;
};

}  // namespace hotmesh::geometry::detail
