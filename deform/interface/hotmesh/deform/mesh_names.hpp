// hotmesh deform: the mesh model the solver works on (hotmesh/mesh), by the short names its
// code uses, as geometry's Vec3.
#pragma once

#include "hotmesh/mesh/element.hpp"
#include "hotmesh/mesh/mesh.hpp"
#include "hotmesh/mesh/mesh_topology.hpp"
#include "hotmesh/mesh/quality.hpp"
#include "hotmesh/mesh/validate.hpp"

namespace hotmesh::deform {

using mesh::CellFace;
using mesh::CellGroup;
using mesh::CellId;
using mesh::ElementList;
using mesh::ElementPoints;
using mesh::ElementType;
using mesh::FaceIndex;
using mesh::kMaxElementFaces;
using mesh::kMaxElementNodes;
using mesh::kMaxFaceNodes;
using mesh::Mesh;
using mesh::NodeId;
using mesh::Patch;
using mesh::QualitySummary;
using mesh::Vec3;

using mesh::bounding_diagonal;
using mesh::dimension;
using mesh::gather;
using mesh::node_count;
using mesh::scaled_jacobian;
using mesh::scaled_jacobians;
using mesh::summarize_quality;

}  // namespace hotmesh::deform
