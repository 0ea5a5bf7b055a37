// hotmesh io: the displacements of a deck's nodes in one DISP block of an .frd, beams and
// shells included. ccx expands a beam, truss, shell or membrane element into a 3D element on
// new nodes: a shell node becomes nodes on its normal through the thickness, a beam node the
// corners (and midsides) of its cross-section. Unless the deck asks *NODE FILE, OUTPUT=2D,
// the .frd holds only those new nodes, and its element block gives each expanded element
// under the number of the element it was made from. The new nodes made of a node lie off the
// element across it (along the normal, in the section plane), so of the element's own nodes
// the nearest to a new node is the node it was made of; its displacement is the mean of
// theirs, which is the mid-surface's or the section centre's for the linear through-thickness
// and section fields of the expansion. Plane and axisymmetric elements are expanded the same
// way, and written so with *NODE FILE, OUTPUT=3D (an axisymmetric one as a thin wedge: the
// mean's radial part is short by 1 - cos of half its angle). A node whose made nodes do not
// lie about it (an offset section, a composite shell's layers written under numbers hotmesh
// does not find) gets no value, and the table asks for OUTPUT=2D.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "fem/frd_index.hpp"
#include "hotmesh/io/calculix.hpp"

namespace hotmesh::io {
namespace {

using geometry::Vec3;

/// The node of `element` (deck numbers) nearest to `at`, if one is nearer than the others
/// (by a millionth of `size`) and nearer than `size`.
std::optional<std::int64_t> nearest_node(const InpDeck& deck, const DeckElement& element, const Vec3& at, double size) {
  std::int64_t nearest = 0;
  double first = std::numeric_limits<double>::infinity(), second = first;
  for (const std::int64_t n : element.nodes) {
    const auto x = deck.nodes.find(n);
    if (x == deck.nodes.end() || n == nearest) continue;
    const double d = distance(x->second, at);
    if (d < first) {
      second = first;
      first = d;
      nearest = n;
    } else if (d < second) {
      second = d;
    }
  }
  if (!(first < size) || !(second - first > 1e-6 * size)) return std::nullopt;
  return nearest;
}

/// The largest distance between two nodes of the element.
double element_size(const InpDeck& deck, const DeckElement& element) {
  double size = 0.0;
  for (std::size_t a = 0; a < element.nodes.size(); ++a) {
    for (std::size_t b = a + 1; b < element.nodes.size(); ++b) {
      const auto xa = deck.nodes.find(element.nodes[a]), xb = deck.nodes.find(element.nodes[b]);
      if (xa != deck.nodes.end() && xb != deck.nodes.end()) size = std::max(size, distance(xa->second, xb->second));
    }
  }
  return size;
}

/// The nodes of .frd element `candidate`, each with the node of the deck element it was made
/// of; empty unless each lies within the element's size of one of the element's nodes,
/// nearer to it than to the others.
std::vector<std::pair<std::int64_t, std::int64_t>> made_by(const FrdResults& results, const InpDeck& deck,
                                                          const DeckElement& element, const std::vector<std::int64_t>& written,
                                                          double size) {
  std::vector<std::pair<std::int64_t, std::int64_t>> pairs;
  for (const std::int64_t made : written) {
    const auto at = results.nodes.find(made);
    const auto from = at == results.nodes.end() ? std::nullopt : nearest_node(deck, element, at->second, size);
    if (!from) return {};
    pairs.emplace_back(*from, made);
  }
  return pairs;
}

/// The .frd nodes ccx made of deck element `id`, each with the node of the element it was made
/// of. ccx writes the expanded element under the element's own number; a composite shell, one
/// element per layer under that number plus 1, 2, ... times the deck's largest element number.
std::vector<std::pair<std::int64_t, std::int64_t>> made_of(const FrdResults& results, const InpDeck& deck, std::int64_t id,
                                                          const DeckElement& element) {
  const double size = element_size(deck, element);
  const std::int64_t last = deck.elements.rbegin()->first;
  std::vector<std::pair<std::int64_t, std::int64_t>> out;
  for (std::size_t layer = 0; layer <= results.elements.size(); ++layer) {
    const auto written = results.elements.find(id + static_cast<std::int64_t>(layer) * last);
    if (written == results.elements.end()) {
      if (layer == 0) continue;
      break;
    }
    const auto pairs = made_by(results, deck, element, written->second, size);
    out.insert(out.end(), pairs.begin(), pairs.end());
  }
  return out;
}

}  // namespace

DeckDisplacements::DeckDisplacements(const FrdResults& results, const InpDeck& deck, const FrdBlock& disp)
    : results_(results), deck_(deck), disp_(disp), index_(detail::block_index(disp)) {
  for (const auto& [id, element] : deck.elements) {
    if (!element.expanded) continue;
    for (const std::int64_t n : element.nodes) {
      if (!index_.contains(n)) expanded_of_[n].push_back(id);
    }
  }
}

std::map<std::int64_t, Vec3> DeckDisplacements::of(const std::vector<std::int64_t>& nodes) const {
  std::map<std::int64_t, Vec3> out;
  std::map<std::int64_t, std::vector<std::int64_t>> made;  // node -> the .frd nodes made of it
  for (const std::int64_t n : nodes) {
    if (const auto it = index_.find(n); it != index_.end()) {
      out[n] = disp_.values[it->second];
      continue;
    }
    const auto elements = expanded_of_.find(n);
    if (elements == expanded_of_.end()) continue;
    std::vector<std::int64_t>& mine = made[n];
    for (const std::int64_t id : elements->second) {
      for (const auto& [from, m] : made_of(results_, deck_, id, deck_.elements.at(id))) {
        if (from == n) mine.push_back(m);
      }
    }
    std::sort(mine.begin(), mine.end());
    mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
  }
  if (made.empty()) return out;  // every node in the .frd: the deck's size is not needed
  const double rounding = 2e-5 * detail::deck_size(deck_);  // the six digits of an ASCII .frd
  for (const auto& [node, from_node] : made) {
    Vec3 sum, centre;
    double spread = 0.0;
    const Vec3 at = deck_.nodes.at(node);
    std::size_t count = 0;
    for (const std::int64_t m : from_node) {
      const auto it = index_.find(m);
      if (it == index_.end()) break;
      sum += disp_.values[it->second];
      centre += results_.nodes.at(m);
      spread = std::max(spread, distance(results_.nodes.at(m), at));
      ++count;
    }
    // The nodes made of it lie about it, unless some are missing (a composite's layer) or the
    // section is offset (OFFSET=): then their mean is not the node's displacement.
    if (count == 0 || count != from_node.size()) continue;
    if (distance(centre / static_cast<double>(count), at) > std::max(0.02 * spread, rounding)) continue;
    out[node] = sum / static_cast<double>(count);
  }
  return out;
}

}  // namespace hotmesh::io
