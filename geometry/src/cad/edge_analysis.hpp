// hotmesh geometry (internal): what a CAD edge is: the kind of its curve, its ends and length.
#pragma once

#include <TopoDS_Edge.hxx>

#include "hotmesh/geometry/cad_model.hpp"

namespace hotmesh::geometry::detail {

/// The edge as `hotmesh cad` lists it, numbered `id`.
EdgeInfo describe_edge(const TopoDS_Edge& edge, int id);

}  // namespace hotmesh::geometry::detail
