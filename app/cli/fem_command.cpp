// hotmesh fem RESULTS.frd [--inp DECK.inp] [--set NAME [-o table.csv]] [--step N | --time T]:
// what a CalculiX results file holds, as a case file's `deflection: {calculix: ...}` would read
// it. Without --set: the output steps (the DISP blocks, with the largest displacement and the
// temperature range of each) and, with --inp, the deck's node sets and surfaces with their
// node counts and largest displacement at the chosen step. With --set: the deflection table
// hotmesh would use, as CSV (io/deflection_csv.hpp), on stdout or into -o (never one of the
// files it read).
#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <map>

#include "cli/commands.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/calculix.hpp"
#include "hotmesh/io/deflection_csv.hpp"
#include "hotmesh/io/output_folder.hpp"

namespace hotmesh::app {

namespace {

struct FemOptions {
  std::string frd;
  std::string inp;
  std::string set;
  std::string output;
  std::string step = "last";
  std::optional<double> time;
};

io::FrdStepChoice step_choice(const FemOptions& o) {
  io::FrdStepChoice choice;
  choice.time = o.time;
  if (o.step == "last") return choice;
  try {
    std::size_t used = 0;
    const int n = std::stoi(o.step, &used);
    if (used == o.step.size() && n >= 1) {
      choice.step = n;
      return choice;
    }
  } catch (const std::exception&) {
  }
  throw InputError("--step: expected `last` or the number of an analysis step (from 1), got '" + o.step + "'");
}

/// The largest displacement of a block or of a set, and the node that has it.
struct Largest {
  double value = 0.0;
  std::int64_t node = 0;
};

Largest largest_displacement(const io::FrdBlock& block) {
  Largest out;
  for (std::size_t i = 0; i < block.nodes.size(); ++i) {
    const double u = norm(block.values[i]);
    if (u > out.value || out.node == 0) out = {u, block.nodes[i]};
  }
  return out;
}

std::string temperature_range(const io::FrdResults& results, const io::FrdBlock& disp) {
  const io::FrdBlock* t = results.companion(disp, "NDTEMP");
  if (t == nullptr || t->values.empty()) return "";
  const auto [lo, hi] = std::minmax_element(t->values.begin(), t->values.end(),
                                            [](const auto& a, const auto& b) { return a.x < b.x; });
  return fmt::format("  temperature {:.6g} to {:.6g}", lo->x, hi->x);
}

std::string steps_text(const io::FrdResults& results) {
  std::string text = fmt::format("{}: {} .frd, {} nodes\n", results.source, results.binary ? "binary" : "ASCII",
                                 results.nodes.size());
  const auto blocks = results.displacements();
  if (blocks.empty()) return text + "  no DISP (displacement) block\n";
  text += "output steps (DISP blocks):\n";
  for (const io::FrdBlock* b : blocks) {
    const Largest u = largest_displacement(*b);
    text += fmt::format("  step {:>3}  increment {:>3}  time {:<12.6g} largest |u| {:.6g} at node {}{}\n", b->step,
                        b->increment, b->time, u.value, u.node, temperature_range(results, *b));
  }
  return text;
}

/// The largest of the set's displacements (DeckDisplacements: beams and shells as ccx
/// expanded them too).
Largest largest_of(const std::map<std::int64_t, geometry::Vec3>& displacements) {
  Largest out;
  for (const auto& [node, u] : displacements) {
    if (norm(u) > out.value || out.node == 0) out = {norm(u), node};
  }
  return out;
}

std::string sets_text(const io::FrdResults& results, const io::InpDeck& deck, const io::FrdBlock& disp) {
  std::string text = fmt::format("{}: {} model, {} nodes, {} elements, {} file(s)\n", deck.file.string(),
                                 io::to_string(deck.kind()), deck.nodes.size(), deck.elements.size(),
                                 deck.files.size());
  text += fmt::format("node sets and surfaces, largest |u| at step {} (time {:.6g}):\n", disp.step, disp.time);
  const io::DeckDisplacements deck_displacements(results, deck, disp);
  const auto list = [&](std::string_view what, const std::map<std::string, io::DeckSet>& sets) {
    for (const auto& [name, set] : sets) {
      if (!set.unusable.empty()) {
        text += fmt::format("  {:<8} {:<24} unusable: the {}\n", what, name, set.unusable);
        continue;
      }
      const std::vector<std::int64_t> nodes = deck.set_nodes(name);
      const auto displacements = deck_displacements.of(nodes);
      const Largest u = largest_of(displacements);
      const std::string without = displacements.size() == nodes.size()
                                      ? std::string()
                                      : fmt::format("  ({} without a value)", nodes.size() - displacements.size());
      text += fmt::format("  {:<8} {:<24} {:>7} nodes  largest |u| {:.6g} at node {}   ({}){}\n", what, name,
                          nodes.size(), u.value, u.node, set.place.text(), without);
    }
  };
  list("nset", deck.nsets);
  list("surface", deck.surfaces);
  return text;
}

int run_fem(const FemOptions& o) {
  if (!o.set.empty() && o.inp.empty()) throw InputError("--set needs --inp: the deck defines the sets");
  if (!o.output.empty() && o.set.empty()) throw InputError("-o writes the table of one set: give --set too");
  const io::FrdStepChoice choice = step_choice(o);
  if (o.set.empty()) {
    const io::FrdResults results = io::read_frd(o.frd);
    std::cout << steps_text(results);
    if (!o.inp.empty()) std::cout << sets_text(results, io::read_inp(o.inp), io::choose_displacements(results, choice));
    return 0;
  }
  const io::CalculixTable table = io::read_calculix_table({o.frd, o.inp, o.set, choice});
  const std::string csv = io::format_deflection_csv(table.samples);
  if (o.output.empty()) {
    std::cout << csv;
    return 0;
  }
  io::refuse_overwriting_input(o.output, table.files);  // the .frd, the deck and its *INCLUDEs
  io::write_file_atomically(o.output, csv);
  std::cout << fmt::format("{}: {} table of set {} ({} nodes), step {} (time {:.6g})\n", o.output,
                           geometry::to_string(table.samples.frame), o.set, table.samples.size(), table.step,
                           table.time);
  return 0;
}

}  // namespace

Command add_fem_command(CLI::App& parent) {
  auto options = std::make_shared<FemOptions>();
  CLI::App* cmd = parent.add_subcommand(
      "fem", "Show the steps, node sets and surfaces of CalculiX results, or write the deflection table of one set");
  cmd->add_option("FRD", options->frd, "CalculiX results file (.frd, ASCII or binary)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--inp", options->inp, "The input deck ccx solved (.inp): its node sets and surfaces")
      ->check(CLI::ExistingFile);
  cmd->add_option("--set", options->set, "Node set or surface of the deck whose table to write (needs --inp)");
  cmd->add_option("-o,--output", options->output, "Write the table to this CSV file (default: stdout); never the .frd, the deck or a file it includes");
  cmd->add_option("--step", options->step, "Analysis step: `last` (default) or its number");
  cmd->add_option("--time", options->time, "Step time of the output to read");
  return [options] { return run_fem(*options); };
}

}  // namespace hotmesh::app
