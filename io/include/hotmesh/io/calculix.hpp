// hotmesh io: FEM results as CalculiX writes them. Three pieces:
//   - the .frd results file (ASCII or binary): its nodes and, per output step, the DISP
//     (displacement) and NDTEMP (temperature) blocks;
//   - the .inp input deck (Abaqus syntax): nodes, elements, *NSET, *ELSET, *SURFACE (element
//     faces turned into their nodes), *INCLUDE files and GENERATE ranges;
//   - the deflection table of one node set or surface at one step, in the frame its elements
//     give: CAX* (axisymmetric, x is r and y is z) meridional, CPS*/CPE* planar, C3D* cartesian.
// The table is the same geometry::DeflectionSamples a CSV table gives, so a `calculix:`
// deflection feeds the same reconstruction. Every problem is an InputError naming the file
// and line. Recipe and format notes: docs/bring-your-own-data.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "hotmesh/geometry/deflection_samples.hpp"
#include "hotmesh/core/vec3.hpp"

namespace hotmesh::io {

// ---------------------------------------------------------------------------------------------
// .frd results

/// One nodal result block of an .frd file (DISP, NDTEMP, ...) at one output step.
struct FrdBlock {
  std::string name;                       ///< "DISP", "NDTEMP", "STRESS", ...
  int step = 0;                           ///< the analysis step (*STEP) it belongs to, 1-based
  int increment = 0;                      ///< the increment within the step
  double time = 0.0;                      ///< the step time ccx writes in the block header
  std::size_t line = 0;                   ///< line of the block header in the file
  std::vector<std::int64_t> nodes;        ///< node numbers, in file order
  std::vector<geometry::Vec3> values;     ///< the first (up to) three components of each node
};

struct FrdResults {
  std::string source;                                ///< file name, for messages
  bool binary = false;                               ///< some block was written in binary
  std::map<std::int64_t, geometry::Vec3> nodes;      ///< the node block: number -> coordinates
  /// The element block: number -> nodes as the .frd writes them. ccx writes a beam or shell
  /// element (B31, B32, S4, S8, T3D2, ... unless *NODE FILE, OUTPUT=2D) as the 3D element it
  /// expanded it into, on new nodes about the element's own.
  std::map<std::int64_t, std::vector<std::int64_t>> elements;
  std::vector<FrdBlock> blocks;                      ///< every nodal result block, in file order

  /// The DISP blocks, in file order.
  std::vector<const FrdBlock*> displacements() const;
  /// The block named `name` written at the same step and increment as `at`, if any.
  const FrdBlock* companion(const FrdBlock& at, std::string_view name) const;
};

/// Parses an .frd file; `source` names it in messages. Throws InputError "<source>:<line>: ..."
/// on a truncated file, a block shorter than its header says, a value that is not a number,
/// a node coordinate, step time, DISP or NDTEMP value that is not finite (nan, inf).
FrdResults parse_frd(std::string_view content, std::string_view source);
FrdResults read_frd(const std::filesystem::path& path);

/// Which output step a table is read from: the last DISP block (default), the last one of an
/// analysis step, or the one at a step time.
struct FrdStepChoice {
  std::optional<int> step;
  std::optional<double> time;
};

/// The DISP block `choice` names. Throws InputError listing the steps (and times) the file has
/// when there is no such block, or when the file has no DISP block at all.
const FrdBlock& choose_displacements(const FrdResults& results, const FrdStepChoice& choice);

// ---------------------------------------------------------------------------------------------
// .inp deck

/// Where something is defined: a file of the deck (the main file or an *INCLUDE) and a line.
struct DeckPlace {
  std::filesystem::path file;
  std::size_t line = 0;
  std::string text() const;  ///< "file:line"
};

/// The kind of model the deck's solid elements make.
enum class ModelKind { axisymmetric, plane, solid };
const char* to_string(ModelKind kind);

struct DeckElement {
  std::string type;                   ///< upper case, e.g. "CAX4", "C3D20R"
  std::vector<std::int64_t> nodes;
  DeckPlace place;
  /// ccx expands it into a 3D element on new nodes, and writes that element to the .frd: a
  /// beam, truss, shell or membrane (B31, B32, T3D2, S4, S8, M3D4, ...) unless told *NODE FILE,
  /// OUTPUT=2D; a plane or axisymmetric element (CPS*, CPE*, CAX*) when told OUTPUT=3D.
  bool expanded = false;
};

/// A node set, element set or surface: its members as written (numbers) and where it is.
struct DeckSet {
  std::string name;                   ///< upper case, as CalculiX keeps names
  std::vector<std::int64_t> members;  ///< node numbers (NSET, node surface) or element numbers (ELSET)
  /// Element surface: the element faces (element number, face 1..6).
  std::vector<std::pair<std::int64_t, int>> faces;
  DeckPlace place;                    ///< its first definition
  /// Why hotmesh cannot give its nodes (a surface of faces of beam or shell elements), with
  /// where; empty when it can. The rest of the deck is read all the same.
  std::string unusable;
};

struct InpDeck {
  std::filesystem::path file;                     ///< the main deck
  std::vector<std::filesystem::path> files;       ///< the main deck, then every *INCLUDEd file, once each
  std::map<std::int64_t, geometry::Vec3> nodes;   ///< number -> coordinates (z = 0 in 2D)
  std::map<std::int64_t, DeckElement> elements;
  std::map<std::string, DeckSet> nsets;
  std::map<std::string, DeckSet> elsets;
  std::map<std::string, DeckSet> surfaces;

  /// The kind the deck's CAX*, CPS*/CPE* and C3D* elements make. Throws InputError when the
  /// deck has none of them, or several kinds.
  ModelKind kind() const;
  /// The nodes of a node set or surface (name in any case), sorted and each once. Throws
  /// InputError listing the node sets and surfaces of the deck when there is no such one.
  std::vector<std::int64_t> set_nodes(std::string_view name) const;
  /// Where the node set or surface `name` is defined (set_nodes found it).
  DeckPlace set_place(std::string_view name) const;
};

/// What a deck may make read_inp read and hold, whatever its counts say: a few kilobytes of
/// deck can name 2^31 *INCLUDE reads (files that include the next one twice) or sets of
/// billions of numbers (GENERATE ranges, sets defined as earlier sets twice over). A deck that
/// would go beyond one is refused at the line that does, naming the count. The defaults are
/// far above the decks hotmesh reads walls from (CalculiX's own examples, a 3D sector of
/// millions of nodes); the fuzz target uses small ones to keep each input quick.
struct InpLimits {
  std::size_t include_depth = 32;          ///< files open at once, the main deck's included files' included files ...
  std::size_t includes = 10'000;           ///< *INCLUDE reads in all (a file included again counts again)
  std::size_t lines = 30'000'000;          ///< data and keyword lines, every *INCLUDE spliced in where it is read
  std::size_t set_members = 30'000'000;    ///< numbers held by all sets together (a surface face: its nodes)
};

/// Reads a deck and the files it includes (paths relative to the including file's folder).
/// Throws InputError "<file>:<line>: ..." on a bad number, an unknown element face, an element
/// defined twice (as CalculiX does), a set that uses an undefined set, an *INCLUDE that is
/// missing or includes itself, a deck beyond `limits`.
InpDeck read_inp(const std::filesystem::path& path, const InpLimits& limits = {});

/// The displacements of the deck's nodes in one DISP block: a node's own value where the
/// block has it; for a node of beam, truss, shell or membrane elements that ccx wrote expanded
/// into 3D elements (the default without *NODE FILE, OUTPUT=2D), the mean of the nodes ccx
/// made of it, which the .frd's element block gives. The block's node index and the deck's
/// expanded elements per node are made once, for the sets of a deck.
class DeckDisplacements {
 public:
  DeckDisplacements(const FrdResults& results, const InpDeck& deck, const FrdBlock& disp);
  /// The displacements of `nodes`; a node with neither value is left out.
  std::map<std::int64_t, geometry::Vec3> of(const std::vector<std::int64_t>& nodes) const;

 private:
  const FrdResults& results_;
  const InpDeck& deck_;
  const FrdBlock& disp_;
  std::unordered_map<std::int64_t, std::size_t> index_;                     ///< node -> place in disp_
  std::unordered_map<std::int64_t, std::vector<std::int64_t>> expanded_of_; ///< node -> its expanded elements
};

// ---------------------------------------------------------------------------------------------
// the table of one set

/// `deflection: {calculix: {frd, inp, set, step | time}}` of a case file.
struct CalculixSelection {
  std::filesystem::path frd;
  std::filesystem::path inp;
  std::string set;
  FrdStepChoice choice;
};

struct CalculixTable {
  geometry::DeflectionSamples samples;        ///< the set's nodes, undeformed, and their DISP
  std::vector<std::filesystem::path> files;   ///< the .frd, the deck and its *INCLUDEs
  ModelKind kind = ModelKind::solid;
  int step = 0;                               ///< the DISP block read
  int increment = 0;
  double time = 0.0;
  /// Temperatures of the set's nodes at that step (NDTEMP), when the .frd has them.
  std::optional<double> min_temperature, max_temperature;
};

/// The deflection table of the set's nodes: coordinates from the deck, displacements from the
/// chosen DISP block. Frame: meridional for axisymmetric decks (r = x, z = y, about the
/// case's axis), planar for plane decks, cartesian for solid ones. Throws InputError when a
/// node of the set has no displacement in that block, or when the .frd's node block puts a
/// node of the set elsewhere than the deck does (results of another model).
CalculixTable read_calculix_table(const CalculixSelection& selection);
CalculixTable calculix_table(const FrdResults& results, const InpDeck& deck, const CalculixSelection& selection);

}  // namespace hotmesh::io
