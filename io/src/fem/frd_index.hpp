// hotmesh io (internal): where each node of an .frd result block is, and the scale of a
// deck's coordinates (calculix_table.cpp, expanded_nodes.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "hotmesh/io/calculix.hpp"

namespace hotmesh::io::detail {

/// Node number -> its place in the block.
inline std::unordered_map<std::int64_t, std::size_t> block_index(const FrdBlock& block) {
  std::unordered_map<std::int64_t, std::size_t> index;
  index.reserve(block.nodes.size());
  for (std::size_t i = 0; i < block.nodes.size(); ++i) index[block.nodes[i]] = i;
  return index;
}

/// The largest coordinate of the deck, the scale of its positions.
inline double deck_size(const InpDeck& deck) {
  double size = 0.0;
  for (const auto& [n, x] : deck.nodes) size = std::max({size, std::abs(x.x), std::abs(x.y), std::abs(x.z)});
  return size;
}

}  // namespace hotmesh::io::detail
