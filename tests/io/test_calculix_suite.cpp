// hotmesh tests: CalculiX's own test suite (Debian's calculix-ccx-test, the reference .frd
// results of ccx 2.11 and their decks). Every reference .frd is read, continuation records of
// blocks with more than six components and all; with its deck, every one that holds
// displacements gives one to each node of the deck's continuum elements and of its beams and
// shells (which ccx writes expanded into 3D elements), and a table of each set of them.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "calculix_suite.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/calculix.hpp"

namespace hotmesh::io {
namespace {

using test::TempDir;

/// The nodes of the deck's continuum elements (CAX*, CPS*, CPE*, C3D*) and of the beams and
/// shells ccx expands: the nodes whose displacements a wall can take.
std::vector<std::int64_t> model_nodes(const InpDeck& deck) {
  std::vector<std::int64_t> nodes;
  for (const auto& [id, element] : deck.elements) {
    const std::string_view type = element.type;
    const bool continuum = type.starts_with("C3D") || type.starts_with("CAX") || type.starts_with("CPS") ||
                           type.starts_with("CPE");
    if (continuum || element.expanded) nodes.insert(nodes.end(), element.nodes.begin(), element.nodes.end());
  }
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

struct SuiteOutcome {
  std::set<std::string> read, without_displacements, without_deck, partly_written, expanded;
};

/// One job: its results read, and with displacements its deck and the tables of its sets.
void check_job(const std::string& job, const TempDir& dir, SuiteOutcome& outcome) {
  const FrdResults results = parse_frd(test::ccx_suite_results_text(job), job + ".frd");
  outcome.read.insert(job);
  if (results.displacements().empty()) {
    outcome.without_displacements.insert(job);
    return;
  }
  if (!test::ccx_suite_text(job + ".inp")) {
    outcome.without_deck.insert(job);
    return;
  }
  const std::filesystem::path inp = test::ccx_suite_deck(dir.path(), job);
  const InpDeck deck = read_inp(inp);
  deck.kind();  // refuses a deck of no continuum or expanded elements
  const FrdBlock& disp = *results.displacements().back();
  const std::vector<std::int64_t> nodes = model_nodes(deck);
  const auto displacements = DeckDisplacements(results, deck, disp).of(nodes);
  if (displacements.size() != nodes.size()) outcome.partly_written.insert(job);
  if (std::any_of(deck.elements.begin(), deck.elements.end(), [](const auto& e) { return e.second.expanded; })) {
    outcome.expanded.insert(job);
  }
  for (const auto* sets : {&deck.nsets, &deck.surfaces}) {
    for (const auto& [name, set] : *sets) {
      if (!set.unusable.empty()) continue;
      const std::vector<std::int64_t> members = deck.set_nodes(name);
      const bool all = !members.empty() && std::all_of(members.begin(), members.end(), [&](std::int64_t n) {
        return displacements.contains(n);
      });
      if (!all) continue;
      const CalculixTable table = calculix_table(results, deck, {job + ".frd", inp, name, {}});
      EXPECT_EQ(table.samples.size(), members.size()) << job << " set " << name;
    }
  }
}

TEST(CalculixSuite, EveryReferenceResultIsReadAndWithDisplacementsGivesTheTablesOfItsDecksSets) {
  if (!test::have_ccx_suite()) GTEST_SKIP() << "Debian's calculix-ccx-test is not installed; scripts/install-deps.sh installs it";
  TempDir dir;
  SuiteOutcome outcome;
  const std::set<std::string> jobs = test::ccx_suite_results();
  for (const std::string& job : jobs) {
    try {
      check_job(job, dir, outcome);
    } catch (const InputError& e) {
      ADD_FAILURE() << job << ": " << e.what();
    }
  }
  EXPECT_GE(jobs.size(), 53u);
  EXPECT_EQ(outcome.read, jobs);
  // Network models (arteries, pipes, air flow), sensitivity analyses, and results the suite
  // keeps only some blocks of (contact, stresses, temperatures, electromagnetic fields), among
  // them twobeam, the global model of submodeltwobeam, whose deck the suite does not have.
  EXPECT_EQ(outcome.without_displacements,
            (std::set<std::string>{"artery3", "artery4", "artery5", "beamcontact", "cubef2f1", "cubef2f2", "cubef2f3",
                                   "induction", "modelchel", "pipe2", "pret1", "primaryair", "sens_orien1",
                                   "sensitivity_I", "sensitivity_V", "sensitivity_VI", "twobeam"}));
  EXPECT_TRUE(outcome.without_deck.empty());
  // Nodes without a displacement: induction2 computes them for the heated part only, not for
  // the air or the coil; contact10 and contact11 offset their shell and beam sections (OFFSET=
  // 0.5), so the nodes ccx makes do not lie about the deck's; shell3's composite layers are
  // written under element numbers hotmesh does not find. For those hotmesh asks for OUTPUT=2D.
  EXPECT_EQ(outcome.partly_written, (std::set<std::string>{"contact10", "contact11", "induction2", "shell3"}));
  // Beams, trusses and shells written expanded (composite shells under new element numbers:
  // concretebeam, shell3), plane elements written with OUTPUT=3D (planestrain, planestrain2).
  EXPECT_THAT(outcome.expanded, ::testing::IsSupersetOf({"b31", "boxprofile", "concretebeam", "contact10", "contact11",
                                                          "pendel", "planestrain", "planestrain2", "section", "shell1",
                                                          "shell3", "simplebeam", "truss", "uprofile"}));
}

}  // namespace
}  // namespace hotmesh::io
