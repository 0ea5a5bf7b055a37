// hotmesh setup: the walls a case's patches follow (their shapes, section 4.2) at a stage of the
// motion, sampled for people to look at: polylines in the x-y plane for 2D cases, surfaces of
// revolution over the angle their patch covers for 3D ones.
#pragma once

#include <span>
#include <vector>

#include "hotmesh/deform/mesh_motion.hpp"
#include "hotmesh/geometry/deflected_curve.hpp"
#include "hotmesh/io/vtu.hpp"
#include "hotmesh/mesh/mesh.hpp"

namespace hotmesh::setup {

/// The stage-lambda curve as a polyline: evenly spaced in its parameter and through every
/// piece end, so its corners are drawn as corners.
std::vector<geometry::Vec2> curve_outline(const geometry::DeflectedCurve& curve, double lambda);

/// Every patch of `motions` with a curve shape (prescribed or sliding), at stage lambda: one
/// polyline each in 2D, one band of quads each in 3D, with the cell array "patch" (the
/// patch's 1-based index in mesh.patches).
io::PolyData deflected_walls(const mesh::Mesh& mesh, std::span<const deform::PatchMotion> motions, double lambda);

}  // namespace hotmesh::setup
