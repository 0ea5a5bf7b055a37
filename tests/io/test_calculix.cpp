// hotmesh tests: the CalculiX readers (io/src/fem/frd_reader.cpp, inp_reader.cpp,
// calculix_table.cpp) against files written by the real ccx: its .frd displacements equal its
// own .dat printout of the same nodes, binary .frd equals ASCII .frd, sets come through
// *INCLUDE and GENERATE, surfaces of element faces give their nodes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "calculix_runs.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/calculix.hpp"

namespace hotmesh::io {
namespace {

using geometry::SampleFrame;
using geometry::Vec3;
using test::RingDeck;
using test::TempDir;

double largest(const std::map<std::int64_t, Vec3>& table) {
  double m = 0.0;
  for (const auto& [n, u] : table) m = std::max({m, std::abs(u.x), std::abs(u.y), std::abs(u.z)});
  return m;
}

/// Every node of `printout` has the same displacement in `block`, to `relative` of the largest.
void expect_block_equals(const FrdBlock& block, const std::map<std::int64_t, Vec3>& printout, double relative) {
  ASSERT_EQ(block.nodes.size(), printout.size());
  const double tolerance = relative * largest(printout);
  for (std::size_t i = 0; i < block.nodes.size(); ++i) {
    const Vec3& expected = printout.at(block.nodes[i]);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(block.values[i][k], expected[k], tolerance) << "node " << block.nodes[i] << " component " << k;
    }
  }
}

/// The ring deck solved by ccx in a temporary folder, with ASCII or binary results.
class SolvedRing : public ::testing::Test {
 protected:
  void solve(const std::string& output) {
    if (!test::have_ccx()) GTEST_SKIP() << "ccx (Debian package calculix-ccx) is not installed; scripts/install-deps.sh installs it";
    ring.write(dir.path(), output);
    const test::CommandResult run = test::run_ccx(dir.path(), "ring");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    printouts = test::dat_displacements(test::read_text(dir / "ring.dat"));
    ASSERT_EQ(printouts.size(), 2u);
  }
  CalculixSelection selection(const std::string& set) const { return {dir / "ring.frd", dir / "ring.inp", set, {}}; }

  TempDir dir;
  RingDeck ring;
  std::vector<std::map<std::int64_t, Vec3>> printouts;
};

TEST_F(SolvedRing, AsciiFrdDisplacementsEqualTheDatPrintout) {
  solve("*NODE FILE");
  const FrdResults results = read_frd(dir / "ring.frd");
  EXPECT_FALSE(results.binary);
  const auto blocks = results.displacements();
  ASSERT_EQ(blocks.size(), 2u);
  for (std::size_t s = 0; s < 2; ++s) {
    EXPECT_EQ(blocks[s]->step, static_cast<int>(s + 1));
    expect_block_equals(*blocks[s], printouts[s], 1e-5);  // the .frd keeps six digits
  }
  EXPECT_EQ(results.nodes.size(), static_cast<std::size_t>((ring.nr + 1) * (ring.nz + 1)));
}

TEST_F(SolvedRing, BinaryFrdDisplacementsEqualTheDatPrintout) {
  solve("*NODE OUTPUT");
  const FrdResults results = read_frd(dir / "ring.frd");
  EXPECT_TRUE(results.binary);
  const auto blocks = results.displacements();
  ASSERT_EQ(blocks.size(), 2u);
  for (std::size_t s = 0; s < 2; ++s) expect_block_equals(*blocks[s], printouts[s], 1e-6);  // 4-byte floats
}

TEST_F(SolvedRing, BinaryFrdEqualsAsciiFrd) {
  solve("*NODE FILE");
  const FrdResults ascii = read_frd(dir / "ring.frd");
  ring.write(dir.path(), "*NODE OUTPUT", "ring_binary");
  ASSERT_EQ(test::run_ccx(dir.path(), "ring_binary").exit_code, 0);
  const FrdResults binary = read_frd(dir / "ring_binary.frd");
  ASSERT_TRUE(binary.binary);
  ASSERT_EQ(ascii.blocks.size(), binary.blocks.size());
  for (std::size_t b = 0; b < ascii.blocks.size(); ++b) {
    const FrdBlock& a = ascii.blocks[b];
    const FrdBlock& c = binary.blocks[b];
    EXPECT_EQ(a.name, c.name);
    EXPECT_EQ(a.step, c.step);
    EXPECT_EQ(a.time, c.time);
    ASSERT_EQ(a.nodes, c.nodes);
    double scale = 0.0;
    for (const Vec3& v : a.values) scale = std::max({scale, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    for (std::size_t i = 0; i < a.values.size(); ++i) {
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(a.values[i][k], c.values[i][k], 1e-5 * scale) << a.name << " node " << a.nodes[i];
    }
  }
  ASSERT_EQ(ascii.nodes.size(), binary.nodes.size());
  for (const auto& [n, x] : ascii.nodes) EXPECT_NEAR(distance(x, binary.nodes.at(n)), 0.0, 1e-6) << "node " << n;
}

TEST_F(SolvedRing, AxisymmetricDeckGivesAMeridionalTableOfTheLastStep) {
  solve("*NODE FILE");
  const CalculixTable table = read_calculix_table(selection("outer"));
  EXPECT_EQ(table.kind, ModelKind::axisymmetric);
  EXPECT_EQ(table.samples.frame, SampleFrame::meridional);
  EXPECT_EQ(table.step, 2);
  ASSERT_EQ(table.samples.size(), static_cast<std::size_t>(ring.nz + 1));
  for (std::size_t j = 0; j < table.samples.size(); ++j) {
    const int row = static_cast<int>(j);
    EXPECT_EQ(table.samples.ids[j], ring.node(ring.nr, row));
    const Vec3 expected = ring.position(ring.nr, row);  // r = x, z = y, as written in the deck
    EXPECT_EQ(table.samples.points[j].x, expected.x);
    EXPECT_EQ(table.samples.points[j].y, expected.y);
    const Vec3 printed = printouts[1].at(ring.node(ring.nr, row));
    EXPECT_NEAR(table.samples.deflections[j].x, printed.x, 1e-5 * largest(printouts[1]));
    EXPECT_NEAR(table.samples.deflections[j].y, printed.y, 1e-5 * largest(printouts[1]));
    EXPECT_EQ(table.samples.deflections[j].z, 0.0);
  }
  ASSERT_TRUE(table.max_temperature.has_value());
  EXPECT_EQ(*table.min_temperature, 200.0);
  EXPECT_EQ(*table.max_temperature, 200.0);
  EXPECT_EQ(table.files.size(), 4u);  // .frd, ring.inp and its two *INCLUDEs
}

TEST_F(SolvedRing, StepOrTimeChoosesTheBlock) {
  solve("*NODE OUTPUT");
  CalculixSelection first = selection("BORE");
  first.choice.step = 1;
  const CalculixTable table = read_calculix_table(first);
  EXPECT_EQ(table.step, 1);
  EXPECT_EQ(*table.max_temperature, 400.0);
  const Vec3 printed = printouts[0].at(1);
  EXPECT_NEAR(table.samples.deflections.front().x, printed.x, 1e-6 * largest(printouts[0]));

  CalculixSelection at_time = selection("BORE");
  at_time.choice.time = 2.0;
  EXPECT_EQ(read_calculix_table(at_time).step, 2);
}

TEST_F(SolvedRing, SetsComeThroughIncludeAndGenerate) {
  solve("*NODE FILE");
  const InpDeck deck = read_inp(dir / "ring.inp");
  EXPECT_EQ(deck.files.size(), 3u);
  std::vector<std::int64_t> bore, top;
  for (int j = 0; j <= ring.nz; ++j) bore.push_back(ring.node(0, j));
  for (int i = 0; i <= ring.nr; ++i) top.push_back(ring.node(i, ring.nz));
  EXPECT_EQ(deck.set_nodes("Bore"), bore);   // names in any case, as in CalculiX
  EXPECT_EQ(deck.set_nodes("TOP"), top);     // the S3 faces (nodes 3-4) of the top row
  EXPECT_EQ(deck.set_place("outer").file, dir / "ring_sets.inp");
  EXPECT_EQ(deck.set_place("outer").line, 4u);
}

TEST_F(SolvedRing, TruncatedFrdNamesTheFileAndSaysSo) {
  solve("*NODE FILE");
  const std::string text = test::read_text(dir / "ring.frd");
  for (const double fraction : {0.3, 0.6, 0.99}) {
    const std::string cut = text.substr(0, static_cast<std::size_t>(fraction * static_cast<double>(text.size())));
    try {
      parse_frd(cut, "cut.frd");
      ADD_FAILURE() << "a file cut at " << fraction << " was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("cut.frd:"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
    }
  }
}

TEST_F(SolvedRing, TruncatedBinaryFrdSaysSo) {
  solve("*NODE OUTPUT");
  const std::string text = test::read_text(dir / "ring.frd");
  const std::size_t disp = text.find("DISP");
  const std::string cut = text.substr(0, disp + 400);
  EXPECT_THROW(
      {
        try {
          parse_frd(cut, "cut.frd");
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
          throw;
        }
      },
      InputError);
}

/// Deterministic pseudo-random numbers (a 64-bit LCG), so a failure can be replayed.
struct Lcg {
  std::uint64_t state = 12345;
  std::size_t below(std::size_t n) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<std::size_t>((state >> 33) % n);
  }
};

TEST_F(SolvedRing, DamagedFrdFilesFailOnlyWithInputErrors) {
  // ccx's own files, ASCII and binary, with bytes overwritten, lines cut out and ends cut off:
  // each is read or refused with an InputError naming the file, nothing else.
  solve("*NODE FILE");
  ring.write(dir.path(), "*NODE OUTPUT", "ring_binary");
  ASSERT_EQ(test::run_ccx(dir.path(), "ring_binary").exit_code, 0);
  Lcg random;
  for (const char* name : {"ring.frd", "ring_binary.frd"}) {
    const std::string original = test::read_text(dir / name);
    for (int trial = 0; trial < 1500; ++trial) {
      std::string damaged = original;
      for (std::size_t k = 0, n = 1 + random.below(4); k < n; ++k) {
        const std::size_t at = random.below(damaged.size());
        switch (random.below(3)) {
          case 0: damaged[at] = static_cast<char>(random.below(256)); break;
          case 1: damaged.erase(at, random.below(80)); break;
          default: damaged.resize(at); break;
        }
        if (damaged.empty()) damaged.push_back(' ');
      }
      try {
        parse_frd(damaged, "damaged.frd");
      } catch (const InputError& e) {
        ASSERT_EQ(std::string(e.what()).rfind("damaged.frd", 0), 0u) << e.what();
      }
    }
  }
}

TEST_F(SolvedRing, DamagedDecksFailOnlyWithInputErrors) {
  // The ring's deck with bytes overwritten, pieces cut out and ends cut off, read with its
  // *INCLUDEs and asked for every set: read or refused with an InputError, nothing else.
  solve("*NODE FILE");
  const std::string original = test::read_text(dir / "ring.inp");
  Lcg random;
  for (int trial = 0; trial < 1000; ++trial) {
    std::string damaged = original;
    for (std::size_t k = 0, n = 1 + random.below(3); k < n && !damaged.empty(); ++k) {
      const std::size_t at = random.below(damaged.size());
      switch (random.below(3)) {
        case 0: damaged[at] = "*,=\n 1Sx"[random.below(9)]; break;
        case 1: damaged.erase(at, random.below(40)); break;
        default: damaged.resize(at); break;
      }
    }
    test::write_text(dir / "damaged.inp", damaged);
    try {
      const InpDeck deck = read_inp(dir / "damaged.inp");
      for (const char* set : {"BORE", "OUTER", "TOP", "BOTTOM", "NALL"}) {
        try {
          deck.set_nodes(set);
        } catch (const InputError&) {  // a set the damage removed
        }
      }
    } catch (const InputError& e) {
      ASSERT_NE(std::string(e.what()).find(".inp"), std::string::npos) << e.what();
    }
  }
}

TEST_F(SolvedRing, ResultsOfAnotherDeckAreRefused) {
  solve("*NODE FILE");
  RingDeck wider = ring;
  wider.r1 = 0.25;  // same numbering, the rim 50 mm further out
  wider.write(dir.path(), "*NODE FILE", "wider");
  try {
    read_calculix_table({dir / "ring.frd", dir / "wider.inp", "OUTER", {}});
    FAIL() << "the ring's results were read for the wider deck";
  } catch (const InputError& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr("ring.frd: node 9 is at (0.200000, 0.000000, 0.000000) here "
                                                            "but at (0.250000, 0.000000, 0.000000) in"))
        << e.what();
  }
}

TEST_F(SolvedRing, MissingStepListsTheStepsThereAre) {
  solve("*NODE FILE");
  CalculixSelection s = selection("BORE");
  s.choice.step = 3;
  try {
    read_calculix_table(s);
    FAIL() << "step 3 was found";
  } catch (const InputError& e) {
    const std::string text = e.what();
    EXPECT_NE(text.find("ring.frd"), std::string::npos) << text;
    EXPECT_NE(text.find("no displacements at step 3"), std::string::npos) << text;
    EXPECT_NE(text.find("step 1 increment 1 (time 1)"), std::string::npos) << text;
    EXPECT_NE(text.find("step 2 increment 1 (time 2)"), std::string::npos) << text;
  }
}

TEST_F(SolvedRing, UnknownSetListsTheSetsOfTheDeck) {
  solve("*NODE FILE");
  try {
    read_calculix_table(selection("RIM"));
    FAIL() << "set RIM was found";
  } catch (const InputError& e) {
    const std::string text = e.what();
    EXPECT_NE(text.find("ring.inp: no node set or surface 'RIM'"), std::string::npos) << text;
    EXPECT_NE(text.find("BORE (3 nodes)"), std::string::npos) << text;
    EXPECT_NE(text.find("OUTER (3 nodes)"), std::string::npos) << text;
    EXPECT_NE(text.find("its surfaces: BOTTOM (9 nodes), TOP (9 nodes)"), std::string::npos) << text;
  }
}

TEST(CalculixSolid, HexDeckGivesACartesianTableOfItsTopFaceEqualToTheDatPrintout) {
  // A 2 x 2 x 1 block of C3D8 elements, clamped below, heated: ccx's .frd against its .dat.
  if (!test::have_ccx()) GTEST_SKIP() << "ccx (Debian package calculix-ccx) is not installed; scripts/install-deps.sh installs it";
  TempDir dir;
  std::string deck = "*NODE, NSET=NALL\n";
  const auto id = [](int i, int j, int k) { return 1 + i + 3 * j + 9 * k; };
  for (int k = 0; k <= 1; ++k) {
    for (int j = 0; j <= 2; ++j) {
      for (int i = 0; i <= 2; ++i) deck += fmt::format("{}, {}, {}, {}\n", id(i, j, k), 0.5 * i, 0.5 * j, 0.25 * k);
    }
  }
  deck += "*ELEMENT, TYPE=C3D8, ELSET=EALL\n";
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      deck += fmt::format("{}, {}, {}, {}, {}, {}, {}, {}, {}\n", 1 + i + 2 * j, id(i, j, 0), id(i + 1, j, 0),
                          id(i + 1, j + 1, 0), id(i, j + 1, 0), id(i, j, 1), id(i + 1, j, 1), id(i + 1, j + 1, 1),
                          id(i, j + 1, 1));
    }
  }
  deck += "*NSET, NSET=BOTTOM, GENERATE\n1, 9, 1\n*SURFACE, NAME=LID\nEALL, S2\n"
          "*MATERIAL, NAME=STEEL\n*ELASTIC\n200e9, 0.3\n*EXPANSION\n1.2e-5\n"
          "*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n*INITIAL CONDITIONS, TYPE=TEMPERATURE\nNALL, 20\n"
          "*STEP\n*STATIC\n*BOUNDARY\nBOTTOM, 1, 3\n*TEMPERATURE\nNALL, 520\n*NODE FILE\nU\n"
          "*NODE PRINT, NSET=NALL\nU\n*END STEP\n";
  test::write_text(dir / "block.inp", deck);
  const test::CommandResult run = test::run_ccx(dir.path(), "block");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto printout = test::dat_displacements(test::read_text(dir / "block.dat"));
  ASSERT_EQ(printout.size(), 1u);

  const CalculixTable table = read_calculix_table({dir / "block.frd", dir / "block.inp", "lid", {}});
  EXPECT_EQ(table.kind, ModelKind::solid);
  EXPECT_EQ(table.samples.frame, SampleFrame::cartesian);
  ASSERT_EQ(table.samples.size(), 9u);  // the nodes of the S2 faces (5-8-7-6): the top
  for (std::size_t n = 0; n < table.samples.size(); ++n) {
    EXPECT_EQ(table.samples.points[n].z, 0.25);
    const Vec3& printed = printout[0].at(table.samples.ids[n]);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(table.samples.deflections[n][k], printed[k], 1e-5 * largest(printout[0]));
  }
  EXPECT_GT(largest(printout[0]), 1e-3);  // 500 degrees hotter: millimetres, up and out
}

// Decks written by hand: element kinds and faces, without ccx.

InpDeck deck_of(const TempDir& dir, const std::string& text) {
  test::write_text(dir / "deck.inp", text);
  return read_inp(dir / "deck.inp");
}

TEST(CalculixInp, HexFacesAndPlaneElementsGiveTheirKinds) {
  TempDir dir;
  const InpDeck hex = deck_of(dir,
                              "*NODE\n1,0,0,0\n2,1,0,0\n3,1,1,0\n4,0,1,0\n5,0,0,1\n6,1,0,1\n7,1,1,1\n8,0,1,1\n"
                              "*ELEMENT, TYPE=C3D8\n1, 1,2,3,4,5,6,7,8\n*SURFACE, NAME=lid\n1, S2\n"
                              "*SURFACE, NAME=side\n1, S4\n");
  EXPECT_EQ(hex.kind(), ModelKind::solid);
  EXPECT_EQ(hex.set_nodes("LID"), (std::vector<std::int64_t>{5, 6, 7, 8}));
  EXPECT_EQ(hex.set_nodes("side"), (std::vector<std::int64_t>{2, 3, 6, 7}));

  const InpDeck plane = deck_of(dir, "*NODE\n1,0,0\n2,1,0\n3,1,1\n4,0,1\n*ELEMENT, TYPE=CPS4\n1, 1,2,3,4\n");
  EXPECT_EQ(plane.kind(), ModelKind::plane);
}

TEST(CalculixInp, QuadraticFacesAddTheirMidsideNodes) {
  TempDir dir;
  // A CAX8 whose element line runs on over two lines, as decks with long elements do.
  const InpDeck deck = deck_of(dir,
                               "*NODE\n1,1,0\n2,2,0\n3,2,1\n4,1,1\n5,1.5,0\n6,2,0.5\n7,1.5,1\n8,1,0.5\n"
                               "*ELEMENT, TYPE=CAX8R, ELSET=E\n1, 1,2,3,4,\n5,6,7,8\n*SURFACE, NAME=S\nE, S2\n");
  EXPECT_EQ(deck.kind(), ModelKind::axisymmetric);
  EXPECT_EQ(deck.set_nodes("s"), (std::vector<std::int64_t>{2, 3, 6}));
}

TEST(CalculixInp, BadLinesNameTheirFileAndLine) {
  TempDir dir;
  const auto problem = [&](const std::string& text) {
    try {
      deck_of(dir, text);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_NE(problem("*NODE\n1, 0, zero\n").find("deck.inp:2: coordinate 2 of node 1 is not a number"), std::string::npos);
  EXPECT_NE(problem("*NSET, NSET=A\n1, B\n").find("deck.inp:2: 'B' is neither a node number nor a *NSET"),
            std::string::npos);
  EXPECT_NE(problem("*NODE\n1,0,0\n*ELEMENT, TYPE=CPS4\n1, 1,1,1,1\n*SURFACE, NAME=X\n1, S7\n").find("deck.inp:6:"),
            std::string::npos);
  EXPECT_NE(problem("*INCLUDE, INPUT=nowhere.inp\n").find("deck.inp:1: *INCLUDE, INPUT=nowhere.inp"), std::string::npos);
  test::write_text(dir / "loop.inp", "*INCLUDE, INPUT=loop.inp\n");
  EXPECT_THROW(read_inp(dir / "loop.inp"), InputError);
}

TEST(CalculixFrd, FileWithoutDisplacementsSaysWhatToAskCcxFor) {
  const std::string frd =
      "    1C\n    2C                             1                                     1\n"
      " -1         1 1.00000E+00 0.00000E+00 0.00000E+00\n -3\n 9999\n";
  const FrdResults results = parse_frd(frd, "temps.frd");
  try {
    choose_displacements(results, {});
    FAIL() << "a DISP block was found";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("temps.frd: no DISP (displacement) block"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hotmesh::io
