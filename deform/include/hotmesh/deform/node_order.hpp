// hotmesh deform: an order of the nodes in which the rows of K are stored, for the locality of
// the stiffness product (reverse Cuthill-McKee).
#pragma once

#include <span>
#include <vector>

#include "hotmesh/deform/stiffness_operator.hpp"

namespace hotmesh::deform {

/// Reverse Cuthill-McKee (George and Liu): order[r] is the node at position r. Each connected
/// part of the mesh starts from a pseudo-peripheral node; a node's unnumbered neighbours
/// follow it by increasing number of cells around them (then node number). Deterministic.
std::vector<NodeId> reverse_cuthill_mckee(const ElementList& cells, const NodeCells& around);

/// The mean of |position(a) - position(b)| over the pairs of corners of every cell, with
/// position[node] given (empty: the nodes' own numbers).
double mean_spread(const ElementList& cells, std::span<const NodeId> position);

}  // namespace hotmesh::deform
