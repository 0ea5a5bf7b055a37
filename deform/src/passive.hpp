// hotmesh deform (internal): passive surfaces (the paper's section 6.1). Before the volume is
// solved, the interior nodes of a passive surface get their displacements from a linear spring
// analogy on the surface mesh alone — springs along the faces' edges, stiffness 1/length —
// driven by the displacements of the surface's rim (its nodes on fixed, prescribed or sliding
// walls). In the volume solve they then act as prescribed. Periodic pairs inside the surface
// are tied (u_s = R u_m), so a passive surface across a periodic sector stays periodic.
#pragma once

#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "hotmesh/deform/mesh.hpp"
#include "periodic.hpp"

namespace hotmesh::deform::detail {

/// Displacement of a rim node (a node of the surface whose motion is known), or nothing for
/// a node the surface solve decides.
using RimDisplacement = std::function<std::optional<Vec3>(NodeId)>;

/// Solves the spring analogy on `patch` at the node positions `points`; returns the
/// displacement of every node of patch.nodes (rim nodes keep theirs). Throws InputError if
/// a part of the surface has no rim (nothing drives it).
std::vector<Vec3> passive_displacements(const Mesh& mesh, std::span<const Vec3> points, const Patch& patch,
                                        const RimDisplacement& rim, const PeriodicCoupling& periodic);

}  // namespace hotmesh::deform::detail
