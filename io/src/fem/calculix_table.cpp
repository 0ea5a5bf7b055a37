// hotmesh io: the deflection table of one CalculiX node set or surface: the deck's node
// coordinates (as written, full precision) and the displacements of one DISP block of the
// .frd, in the frame the deck's elements give. CalculiX's axisymmetric elements take x as
// the radius and y as the axial coordinate, so an axisymmetric deck gives (r, z) = (x, y)
// and (dr, dz) = (D1, D2): the meridional table about the case's axis, whose z origin is the
// deck's y = 0.
#include <algorithm>
#include <cmath>

#include "fem/frd_index.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/calculix.hpp"

namespace hotmesh::io {
namespace {

using geometry::SampleFrame;
using geometry::Vec3;

SampleFrame frame_of(ModelKind kind) {
  switch (kind) {
    case ModelKind::axisymmetric: return SampleFrame::meridional;
    case ModelKind::plane: return SampleFrame::planar;
    case ModelKind::solid: return SampleFrame::cartesian;
  }
  return SampleFrame::cartesian;
}

/// Keeps the components the frame has: (x, y, 0) in 2D and meridional frames.
Vec3 in_frame(const Vec3& v, SampleFrame frame) {
  return frame == SampleFrame::cartesian ? v : Vec3{v.x, v.y, 0.0};
}

std::string block_name(const FrdBlock& b) {
  return "the DISP block of step " + std::to_string(b.step) + " (line " + std::to_string(b.line) + ")";
}

void add_temperatures(const FrdResults& results, const FrdBlock& disp, const std::vector<std::int64_t>& nodes,
                      CalculixTable& table) {
  const FrdBlock* temperatures = results.companion(disp, "NDTEMP");
  if (temperatures == nullptr) return;
  const auto index = detail::block_index(*temperatures);
  for (const std::int64_t n : nodes) {
    const auto it = index.find(n);
    if (it == index.end()) continue;
    const double t = temperatures->values[it->second].x;
    table.min_temperature = std::min(table.min_temperature.value_or(t), t);
    table.max_temperature = std::max(table.max_temperature.value_or(t), t);
  }
}

/// The .frd's node block must place the set's nodes where the deck does (to the six digits an
/// ASCII .frd keeps): results of another model, or of an older deck, are refused.
void require_same_model(const FrdResults& results, const InpDeck& deck, const std::vector<std::int64_t>& nodes) {
  const double tolerance = 2e-5 * detail::deck_size(deck);
  for (const std::int64_t n : nodes) {
    const auto in_frd = results.nodes.find(n);
    const auto in_deck = deck.nodes.find(n);
    if (in_frd == results.nodes.end() || in_deck == deck.nodes.end()) continue;  // reported by the caller
    const Vec3 a = in_deck->second, b = in_frd->second;
    if (!(std::hypot(a.x - b.x, a.y - b.y, a.z - b.z) <= tolerance)) {  // a NaN is no match either
      throw InputError::in(results.source, "node " + std::to_string(n) + " is at (" + std::to_string(b.x) + ", " +
                                               std::to_string(b.y) + ", " + std::to_string(b.z) + ") here but at (" +
                                               std::to_string(a.x) + ", " + std::to_string(a.y) + ", " +
                                               std::to_string(a.z) + ") in " + deck.file.string() +
                                               ": the results are not of this deck (solve it again with ccx?)");
    }
  }
}

[[noreturn]] void missing_displacement(const FrdResults& results, const InpDeck& deck, const FrdBlock& disp,
                                       std::int64_t node, const std::string& set) {
  const auto expanded = std::find_if(deck.elements.begin(), deck.elements.end(), [&](const auto& e) {
    return e.second.expanded && std::find(e.second.nodes.begin(), e.second.nodes.end(), node) != e.second.nodes.end();
  });
  const std::string what = "node " + std::to_string(node) + " of set " + set + " has no value in " + block_name(disp);
  if (expanded != deck.elements.end()) {
    throw InputError::in(results.source, what + ", nor can hotmesh take it from the nodes ccx expands its " +
                                             expanded->second.type + " element " + std::to_string(expanded->first) +
                                             " into (not written, an offset section, a composite's layers); write *NODE FILE, OUTPUT=2D with U in the deck's step, and ccx "
                                             "writes the displacements of the deck's own nodes");
  }
  throw InputError::in(results.source, what + "; write U for all nodes of the set (*NODE FILE without NSET, or with a "
                                              "set that holds it)");
}

}  // namespace

CalculixTable calculix_table(const FrdResults& results, const InpDeck& deck, const CalculixSelection& selection) {
  const std::vector<std::int64_t> nodes = deck.set_nodes(selection.set);
  const DeckPlace set_place = deck.set_place(selection.set);
  if (nodes.empty()) throw InputError::at(set_place.file.string(), set_place.line, "the set '" + selection.set + "' has no nodes");
  const FrdBlock& disp = choose_displacements(results, selection.choice);
  require_same_model(results, deck, nodes);

  CalculixTable table;
  table.kind = deck.kind();
  table.step = disp.step;
  table.increment = disp.increment;
  table.time = disp.time;
  table.files.push_back(selection.frd);
  table.files.insert(table.files.end(), deck.files.begin(), deck.files.end());

  geometry::DeflectionSamples& samples = table.samples;
  samples.frame = frame_of(table.kind);
  samples.source = set_place.text() + " (set " + selection.set + ", displacements from " + results.source + ")";
  const std::map<std::int64_t, Vec3> displacements = DeckDisplacements(results, deck, disp).of(nodes);
  for (const std::int64_t n : nodes) {
    const auto x = deck.nodes.find(n);
    if (x == deck.nodes.end()) {
      throw InputError::at(set_place.file.string(), set_place.line,
                           "node " + std::to_string(n) + " of set " + selection.set + " is not defined by a *NODE line");
    }
    const auto d = displacements.find(n);
    if (d == displacements.end()) missing_displacement(results, deck, disp, n, selection.set);
    const Vec3 u = d->second;
    if (!std::isfinite(u.x) || !std::isfinite(u.y) || !std::isfinite(u.z)) {
      throw InputError::in(results.source, "node " + std::to_string(n) + " has a displacement that is not a finite number in " +
                                               block_name(disp));
    }
    if (samples.frame == SampleFrame::meridional && x->second.x < 0.0) {
      throw InputError::at(set_place.file.string(), set_place.line,
                           "node " + std::to_string(n) + " of set " + selection.set + " has x = " +
                               std::to_string(x->second.x) + " < 0; in an axisymmetric deck x is the radius");
    }
    samples.points.push_back(in_frame(x->second, samples.frame));
    samples.deflections.push_back(in_frame(u, samples.frame));
    samples.ids.push_back(n);
  }
  add_temperatures(results, disp, nodes, table);
  return table;
}

CalculixTable read_calculix_table(const CalculixSelection& selection) {
  const InpDeck deck = read_inp(selection.inp);
  const FrdResults results = read_frd(selection.frd);
  return calculix_table(results, deck, selection);
}

}  // namespace hotmesh::io
