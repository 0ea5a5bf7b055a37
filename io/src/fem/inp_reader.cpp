// hotmesh io: reader of the parts of a CalculiX (Abaqus syntax) input deck that locate FEM
// results: *NODE, *ELEMENT, *NSET, *ELSET (with GENERATE), *SURFACE (TYPE=ELEMENT faces
// S1..S6, or TYPE=NODE) and *INCLUDE. Other keywords are skipped. Lines are read by ccx's
// rules: keywords and names are case-insensitive (kept upper case), "**" starts a comment
// line, a set may use the sets defined before it, a *NODE coordinate left out or empty is 0
// and fields after z are not read, an element takes its type's node count of nodes over as
// many lines as they need and no more. Beams, trusses, shells and membranes (which ccx
// expands into 3D elements) are kept, marked `expanded`; a surface of their faces is kept as
// unusable, with the reason, and the rest of the deck is read. Element faces follow
// CalculiX's numbering:
//   quadrilaterals (CAX4, CPS8, ...)  S1 1-2, S2 2-3, S3 3-4, S4 4-1
//   triangles (CAX3, CPE6, ...)       S1 1-2, S2 2-3, S3 3-1
//   hexahedra (C3D8, C3D20R, ...)     S1 1-2-3-4, S2 5-8-7-6, S3 1-5-6-2, S4 2-6-7-3,
//                                     S5 3-7-8-4, S6 4-8-5-1
//   tetrahedra (C3D4, C3D10)          S1 1-2-3, S2 1-4-2, S3 2-4-3, S4 3-4-1
//   wedges (C3D6, C3D15)              S1 1-2-3, S2 4-5-6, S3 1-2-5-4, S4 2-3-6-5, S5 3-1-4-6
// and a quadratic element's face adds the midside node of each of its edges.
#include "hotmesh/io/calculix.hpp"

#include <algorithm>
#include <deque>
#include <set>
#include <span>
#include <utility>

#include "fem/calculix_text.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/atomic_file.hpp"

namespace hotmesh::io {
namespace {

namespace fs = std::filesystem;
using detail::field_double;
using detail::field_integer;

// ---------------------------------------------------------------------------------------------
// element families: corner nodes of each face, midside node of each edge (1-based)

struct Edge {
  int a, b, mid;
};

struct Family {
  std::string_view name;
  int corners;
  std::vector<std::vector<int>> faces;
  std::vector<Edge> edges;  ///< of the quadratic element
};

const Family kQuad{"quadrilateral", 4, {{1, 2}, {2, 3}, {3, 4}, {4, 1}}, {{1, 2, 5}, {2, 3, 6}, {3, 4, 7}, {4, 1, 8}}};
const Family kTriangle{"triangle", 3, {{1, 2}, {2, 3}, {3, 1}}, {{1, 2, 4}, {2, 3, 5}, {3, 1, 6}}};
const Family kHex{"hexahedron",
                  8,
                  {{1, 2, 3, 4}, {5, 8, 7, 6}, {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 8, 4}, {4, 8, 5, 1}},
                  {{1, 2, 9}, {2, 3, 10}, {3, 4, 11}, {4, 1, 12}, {5, 6, 13}, {6, 7, 14}, {7, 8, 15}, {8, 5, 16},
                   {1, 5, 17}, {2, 6, 18}, {3, 7, 19}, {4, 8, 20}}};
const Family kTet{"tetrahedron",
                  4,
                  {{1, 2, 3}, {1, 4, 2}, {2, 4, 3}, {3, 4, 1}},
                  {{1, 2, 5}, {2, 3, 6}, {3, 1, 7}, {1, 4, 8}, {2, 4, 9}, {3, 4, 10}}};
const Family kWedge{"wedge",
                    6,
                    {{1, 2, 3}, {4, 5, 6}, {1, 2, 5, 4}, {2, 3, 6, 5}, {3, 1, 4, 6}},
                    {{1, 2, 7}, {2, 3, 8}, {3, 1, 9}, {4, 5, 10}, {5, 6, 11}, {6, 4, 12}, {1, 4, 13}, {2, 5, 14},
                     {3, 6, 15}}};

/// What hotmesh knows of an element type: its node count as ccx reads it, and either the
/// family of a continuum element (faces, kind) or that ccx expands it into a 3D element (beams,
/// trusses, shells, membranes: kind solid, no faces hotmesh knows).
struct ElementShape {
  const Family* family = nullptr;
  int nodes = 0;
  ModelKind kind = ModelKind::solid;
  bool expanded = false;
};

/// The number after a type's letters ("C3D20R" after "C3D": 20).
std::optional<int> leading_number(std::string_view digits) {
  const std::size_t end = std::min(digits.find_first_not_of("0123456789"), digits.size());
  const auto n = field_integer(digits.substr(0, end));
  return n ? std::optional<int>(static_cast<int>(*n)) : std::nullopt;
}

/// Beams, trusses, shells and membranes, which ccx expands into 3D elements: their node count.
std::optional<int> expanded_nodes(std::string_view type) {
  if (type.starts_with("B31") || type.starts_with("T3D2")) return 2;
  if (type.starts_with("B32") || type.starts_with("T3D3")) return 3;
  const bool shell = type.size() >= 2 && type[0] == 'S' && std::string_view("3468").find(type[1]) != std::string_view::npos;
  if (shell) return type[1] - '0';
  if (type.starts_with("M3D")) return leading_number(type.substr(3));
  return std::nullopt;
}

std::optional<ElementShape> shape_of(std::string_view type) {
  ElementShape shape;
  if (const auto n = expanded_nodes(type)) {
    shape.nodes = *n;
    shape.expanded = true;
    return shape;
  }
  std::string_view digits;
  if (type.starts_with("CAX") || type.starts_with("CPS") || type.starts_with("CPE")) {
    shape.kind = type.starts_with("CAX") ? ModelKind::axisymmetric : ModelKind::plane;
    digits = type.substr(3);
  } else if (type.starts_with("C3D")) {
    digits = type.substr(3);
  } else {
    return std::nullopt;
  }
  const auto n = leading_number(digits);
  if (!n) return std::nullopt;
  shape.nodes = *n;
  const bool flat = shape.kind != ModelKind::solid;
  if (flat && (shape.nodes == 4 || shape.nodes == 8)) shape.family = &kQuad;
  if (flat && (shape.nodes == 3 || shape.nodes == 6)) shape.family = &kTriangle;
  if (!flat && (shape.nodes == 8 || shape.nodes == 20)) shape.family = &kHex;
  if (!flat && (shape.nodes == 4 || shape.nodes == 10)) shape.family = &kTet;
  if (!flat && (shape.nodes == 6 || shape.nodes == 15)) shape.family = &kWedge;
  if (shape.family == nullptr) return std::nullopt;
  return shape;
}

/// The node count ccx reads for an element type (its `nope`): continuum and expanded elements,
/// fluid (F3D*), springs, dashpots, gaps, masses, couplings and network elements. None for a
/// user element (U*), whose count its *USER ELEMENT gives.
std::optional<int> ccx_node_count(std::string_view type) {
  if (const auto shape = shape_of(type)) return shape->nodes;
  if (type.starts_with("F3D")) return leading_number(type.substr(3));
  if (type.starts_with("SPRING1") || type.starts_with("DCOUP3D") || type.starts_with("MASS")) return 1;
  if (type.starts_with("SPRING") || type.starts_with("DASHPOT") || type.starts_with("G")) return 2;
  if (type.starts_with("D")) return 3;  // network elements
  return std::nullopt;
}

/// The nodes face `face` (1-based) of an element of this shape has (face_nodes below): its
/// corners, and the midside node of each of its edges when the element is quadratic.
std::size_t face_node_count(const ElementShape& shape, int face) {
  const std::size_t corners = shape.family->faces[static_cast<std::size_t>(face - 1)].size();
  if (shape.nodes == shape.family->corners) return corners;
  return corners + (corners == 2 ? 1 : corners);  // a 2D face is one edge
}

// ---------------------------------------------------------------------------------------------
// the deck as lines, *INCLUDEs spliced in

struct DeckLine {
  std::string_view text;
  std::size_t file = 0;  ///< index into InpDeck::files
  std::size_t line = 0;
};

struct Keyword {
  std::string name;                                     ///< upper case, without '*'
  std::vector<std::pair<std::string, std::string>> parameters;  ///< NAME (upper case) = value as written
  std::optional<std::string> parameter(std::string_view key) const {
    for (const auto& [k, v] : parameters) {
      if (k == key) return v;
    }
    return std::nullopt;
  }
};

/// A deck line's comma-separated fields; a trailing comma adds no empty field.
std::vector<std::string_view> deck_fields(std::string_view line) {
  std::vector<std::string_view> fields = split_fields(line);
  if (fields.size() > 1 && fields.back().empty()) fields.pop_back();  // a trailing comma
  return fields;
}

Keyword parse_keyword(std::string_view text) {
  const std::vector<std::string_view> fields = deck_fields(text.substr(1));
  Keyword keyword{ascii_upper(fields.front()), {}};
  for (std::size_t i = 1; i < fields.size(); ++i) {
    const std::size_t eq = fields[i].find('=');
    const std::string key = ascii_upper(trim(fields[i].substr(0, eq)));
    const std::string value = eq == std::string_view::npos ? "" : std::string(trim(fields[i].substr(eq + 1)));
    keyword.parameters.emplace_back(key, value);
  }
  return keyword;
}

bool is_keyword(std::string_view text) { return text.starts_with('*') && !text.starts_with("**"); }
bool is_comment(std::string_view text) { return text.starts_with("**") || trim(text).empty(); }

/// The deck's lines in reading order, each *INCLUDE's lines spliced in where it stands. A file
/// is read once however often it is included; InpLimits bounds the reads and lines.
class DeckLines {
 public:
  DeckLines(InpDeck& deck, const InpLimits& limits) : deck_(deck), limits_(limits) {}

  std::vector<DeckLine> read(const fs::path& file) {
    std::vector<fs::path> chain;
    add(file, chain);
    return std::move(lines_);
  }

 private:
  /// Splices in `file`, included through `chain` (the files that include it, the main deck first).
  void add(const fs::path& file, std::vector<fs::path>& chain) {
    if (std::find(chain.begin(), chain.end(), file) != chain.end()) {
      throw InputError::in(chain.back().string(), "*INCLUDE of " + file.string() + " includes itself (through " +
                                                      std::to_string(chain.size()) + " files)");
    }
    if (chain.size() > limits_.include_depth) {
      throw InputError::in(file.string(), "*INCLUDEs nested deeper than " + std::to_string(limits_.include_depth) + " files");
    }
    const auto [index, text] = load(file);
    std::size_t number = 0;
    for (std::size_t at = 0; at <= text.size();) {
      const std::size_t eol = std::min(text.find('\n', at), text.size());
      std::string_view line = text.substr(at, eol - at);
      at = eol + 1;
      ++number;
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      if (is_comment(line)) continue;
      if (is_keyword(line) && parse_keyword(line).name == "INCLUDE") {
        chain.push_back(file);
        include(parse_keyword(line), file, number, chain);
        chain.pop_back();
        continue;
      }
      if (lines_.size() == limits_.lines) {
        throw InputError::at(file.string(), number, "the deck has more than " + std::to_string(limits_.lines) +
                                                        " lines, its *INCLUDEs spliced in (a file included again "
                                                        "counts again)");
      }
      lines_.push_back({line, index, number});
    }
  }

  /// The file's index in InpDeck::files and its text, read the first time it is named.
  std::pair<std::size_t, std::string_view> load(const fs::path& file) {
    const auto [known, added] = indices_.try_emplace(file, deck_.files.size());
    if (added) {
      deck_.files.push_back(file);
      contents_.push_back(read_file(file));
    }
    return {known->second, contents_[known->second]};
  }

  void include(const Keyword& keyword, const fs::path& file, std::size_t line, std::vector<fs::path>& chain) {
    const auto input = keyword.parameter("INPUT");
    const std::string place = file.string();
    if (!input || input->empty()) throw InputError::at(place, line, "*INCLUDE needs INPUT=<file>");
    if (++includes_ > limits_.includes) {
      throw InputError::at(place, line, "more than " + std::to_string(limits_.includes) +
                                            " *INCLUDE reads for one deck (a file included again counts again): "
                                            "do files include the next one more than once?");
    }
    std::string name = *input;
    if (name.size() >= 2 && name.front() == '"' && name.back() == '"') name = name.substr(1, name.size() - 2);
    const fs::path path = (fs::path(name).is_absolute() ? fs::path(name) : file.parent_path() / name).lexically_normal();
    if (const std::string problem = input_file_problem(path); !problem.empty()) {
      throw InputError::at(place, line, "*INCLUDE, INPUT=" + name + ": " + path.string() + " " + problem +
                                            " (relative to the including file's folder)");
    }
    add(path, chain);
  }

  InpDeck& deck_;
  const InpLimits& limits_;
  std::map<fs::path, std::size_t> indices_;  ///< file -> index into InpDeck::files and contents_
  std::deque<std::string> contents_;         ///< the files' text; lines_ points into it
  std::size_t includes_ = 0;
  std::vector<DeckLine> lines_;
};

// ---------------------------------------------------------------------------------------------
// the cards

class DeckParser {
 public:
  DeckParser(InpDeck& deck, const InpLimits& limits) : deck_(deck), limits_(limits) {}

  void parse(const std::vector<DeckLine>& lines) {
    for (std::size_t i = 0; i < lines.size();) {
      const DeckLine& head = lines[i];
      if (!is_keyword(head.text)) fail(head, "data line before any keyword; a deck starts with a *KEYWORD line");
      std::size_t end = i + 1;
      while (end < lines.size() && !is_keyword(lines[end].text)) ++end;
      card(parse_keyword(head.text), head, std::span(lines).subspan(i + 1, end - i - 1));
      i = end;
    }
  }

 private:
  [[noreturn]] void fail(const DeckLine& at, const std::string& message) const {
    throw InputError::at(deck_.files[at.file].string(), at.line, message);
  }

  DeckPlace place(const DeckLine& at) const { return {deck_.files[at.file], at.line}; }

  void card(const Keyword& keyword, const DeckLine& head, std::span<const DeckLine> data) {
    if (keyword.name == "NODE") nodes(keyword, head, data);
    if (keyword.name == "ELEMENT") elements(keyword, head, data);
    if (keyword.name == "NSET") members(keyword, head, data, "NSET", deck_.nsets, "node");
    if (keyword.name == "ELSET") members(keyword, head, data, "ELSET", deck_.elsets, "element");
    if (keyword.name == "SURFACE") surface(keyword, head, data);
  }

  std::string set_name(const Keyword& keyword, const DeckLine& head, std::string_view key) const {
    const auto name = keyword.parameter(key);
    if (!name || name->empty()) fail(head, "*" + keyword.name + " needs " + std::string(key) + "=<name>");
    return ascii_upper(*name);
  }

  DeckSet& set_in(std::map<std::string, DeckSet>& sets, const std::string& name, const DeckLine& head) {
    DeckSet& set = sets[name];
    if (set.name.empty()) set = DeckSet{name, {}, {}, place(head)};
    return set;
  }

  std::string beyond_set_limit() const {
    return "more than the " + std::to_string(limits_.set_members) + " numbers hotmesh holds in all sets of a deck";
  }

  /// Counts `count` more numbers into the deck's sets (InpLimits::set_members), before they
  /// are added: the line that would go beyond the limit is refused, nothing is allocated for it.
  void add_members(const DeckLine& at, std::uint64_t count) {
    const std::uint64_t room = limits_.set_members - set_members_;
    if (count > room) {
      fail(at, "this line adds " + std::to_string(count) + " numbers to the deck's sets, which hold " +
                   std::to_string(set_members_) + " already: " + beyond_set_limit() +
                   " (sets defined as earlier sets over and over?)");
    }
    set_members_ += static_cast<std::size_t>(count);
  }

  std::int64_t number(const DeckLine& at, std::string_view field, std::string_view what) const {
    const auto n = field_integer(field);
    if (!n) fail(at, "expected " + std::string(what) + " number, got '" + std::string(field) + "'");
    return *n;
  }

  /// *NODE lines as ccx reads them: `number[, x[, y[, z]]]`, a coordinate left out or empty is
  /// 0, fields after the fourth are not read.
  void nodes(const Keyword& keyword, const DeckLine& head, std::span<const DeckLine> data) {
    DeckSet* set = keyword.parameter("NSET") ? &set_in(deck_.nsets, set_name(keyword, head, "NSET"), head) : nullptr;
    for (const DeckLine& line : data) {
      const std::vector<std::string_view> fields = deck_fields(line.text);
      const std::int64_t id = number(line, fields[0], "a node");
      geometry::Vec3 x;
      for (std::size_t k = 1; k < std::min<std::size_t>(fields.size(), 4); ++k) {
        if (trim(fields[k]).empty()) continue;
        const auto value = field_double(fields[k]);
        if (!value || !std::isfinite(*value)) {
          fail(line, "coordinate " + std::to_string(k) + " of node " + std::to_string(id) + " is not a number: '" +
                         std::string(fields[k]) + "'");
        }
        x[static_cast<int>(k - 1)] = *value;
      }
      deck_.nodes[id] = x;
      if (set != nullptr) {
        add_members(line, 1);
        set->members.push_back(id);
      }
    }
  }

  /// *ELEMENT lines as ccx reads them: the element number, then its type's node count of
  /// nodes over as many lines as they take; nodes after that count on a line are not read. A
  /// user element (U*), whose count hotmesh does not know, continues while a line ends with ','.
  void elements(const Keyword& keyword, const DeckLine& head, std::span<const DeckLine> data) {
    const auto type = keyword.parameter("TYPE");
    if (!type || type->empty()) fail(head, "*ELEMENT needs TYPE=<element type>, e.g. TYPE=CAX8");
    const std::string type_name = ascii_upper(*type);
    const std::optional<int> count = ccx_node_count(type_name);
    const std::optional<ElementShape> shape = shape_of(type_name);
    DeckSet* set = keyword.parameter("ELSET") ? &set_in(deck_.elsets, set_name(keyword, head, "ELSET"), head) : nullptr;
    for (std::size_t i = 0; i < data.size(); ++i) {
      const DeckLine& first = data[i];
      const std::vector<std::string_view> fields = deck_fields(first.text);
      const std::int64_t id = number(first, fields[0], "an element");
      DeckElement element{type_name, {}, place(first), shape && (shape->expanded || shape->kind != ModelKind::solid)};
      const auto add_nodes = [&](const DeckLine& line, std::span<const std::string_view> nodes) {
        for (const std::string_view n : nodes) {
          if (count && element.nodes.size() == static_cast<std::size_t>(*count)) return;
          element.nodes.push_back(number(line, n, "a node"));
        }
      };
      add_nodes(first, std::span(fields).subspan(1));
      const auto wants_more = [&](std::string_view text) {
        if (count) return element.nodes.size() < static_cast<std::size_t>(*count);
        return trim(text).ends_with(',');
      };
      for (std::string_view last = first.text; wants_more(last) && i + 1 < data.size();) {
        last = data[++i].text;
        add_nodes(data[i], deck_fields(last));
      }
      if (count && element.nodes.size() != static_cast<std::size_t>(*count)) {
        fail(first, "element " + std::to_string(id) + " of type " + type_name + " has " +
                        std::to_string(element.nodes.size()) + " nodes before the next keyword, the type " +
                        std::to_string(*count));
      }
      if (const auto defined = deck_.elements.find(id); defined != deck_.elements.end()) {
        fail(first, "element " + std::to_string(id) + " is defined already, at " + defined->second.place.text() +
                        "; CalculiX refuses a deck that defines an element twice");
      }
      deck_.elements.emplace(id, std::move(element));
      if (set != nullptr) {
        add_members(first, 1);
        set->members.push_back(id);
      }
    }
  }

  /// *NSET / *ELSET: numbers, names of sets defined before, or GENERATE ranges `first, last[, step]`.
  void members(const Keyword& keyword, const DeckLine& head, std::span<const DeckLine> data, std::string_view key,
               std::map<std::string, DeckSet>& sets, std::string_view what) {
    DeckSet& set = set_in(sets, set_name(keyword, head, key), head);
    const bool generate = keyword.parameter("GENERATE").has_value();
    for (const DeckLine& line : data) {
      const std::vector<std::string_view> fields = deck_fields(line.text);
      if (generate) {
        generate_range(line, fields, set.members);
        continue;
      }
      for (const std::string_view field : fields) {
        if (field.empty()) continue;
        if (const auto n = field_integer(field)) {
          add_members(line, 1);
          set.members.push_back(*n);
          continue;
        }
        const auto other = sets.find(ascii_upper(field));
        if (other == sets.end()) {
          fail(line, "'" + std::string(field) + "' is neither a " + std::string(what) + " number nor a *" +
                         std::string(key) + " defined before this line");
        }
        add_members(line, other->second.members.size());
        const std::vector<std::int64_t> copy = other->second.members;  // set may be other->second
        set.members.insert(set.members.end(), copy.begin(), copy.end());
      }
    }
  }

  /// `first, last[, increment]`: first, first + increment, ... up to last. The count is taken
  /// in unsigned arithmetic, where last - first of any two 64-bit numbers fits.
  void generate_range(const DeckLine& line, const std::vector<std::string_view>& fields, std::vector<std::int64_t>& out) {
    if (fields.size() < 2 || fields.size() > 3) fail(line, "a GENERATE line is `first, last[, increment]`");
    const std::int64_t first = number(line, fields[0], "a first");
    const std::int64_t last = number(line, fields[1], "a last");
    const std::int64_t step = fields.size() == 3 ? number(line, fields[2], "an increment") : 1;
    if (step < 1 || last < first) fail(line, "a GENERATE range needs first <= last and an increment >= 1");
    const std::uint64_t span = static_cast<std::uint64_t>(last) - static_cast<std::uint64_t>(first);
    const std::uint64_t steps = span / static_cast<std::uint64_t>(step);  // the count is steps + 1
    if (steps >= limits_.set_members) {
      fail(line, "a GENERATE range of " + (steps == UINT64_MAX ? "2^64" : std::to_string(steps + 1)) + " numbers: " +
                     beyond_set_limit());
    }
    add_members(line, steps + 1);
    for (std::uint64_t k = 0; k <= steps; ++k) {
      out.push_back(static_cast<std::int64_t>(static_cast<std::uint64_t>(first) + k * static_cast<std::uint64_t>(step)));
    }
  }

  void surface(const Keyword& keyword, const DeckLine& head, std::span<const DeckLine> data) {
    DeckSet& set = set_in(deck_.surfaces, set_name(keyword, head, "NAME"), head);
    const std::string type = ascii_upper(keyword.parameter("TYPE").value_or("ELEMENT"));
    if (type != "ELEMENT" && type != "NODE") fail(head, "*SURFACE TYPE=" + type + ": expected ELEMENT or NODE");
    for (const DeckLine& line : data) {
      const std::vector<std::string_view> fields = deck_fields(line.text);
      if (type == "NODE") {
        node_surface_line(line, fields.front(), set);
      } else {
        face_surface_line(line, fields, set);
      }
    }
  }

  void node_surface_line(const DeckLine& line, std::string_view field, DeckSet& set) {
    if (const auto n = field_integer(field)) {
      add_members(line, 1);
      set.members.push_back(*n);
      return;
    }
    const auto nset = deck_.nsets.find(ascii_upper(field));
    if (nset == deck_.nsets.end()) fail(line, "'" + std::string(field) + "' is neither a node number nor a *NSET defined before this line");
    add_members(line, nset->second.members.size());
    set.members.insert(set.members.end(), nset->second.members.begin(), nset->second.members.end());
  }

  void face_surface_line(const DeckLine& line, const std::vector<std::string_view>& fields, DeckSet& set) {
    if (fields.size() != 2) fail(line, "an element surface line is `element or element set, S<face>`, e.g. `EDISC, S2`");
    std::vector<std::int64_t> elements;
    if (const auto n = field_integer(fields[0])) {
      elements.push_back(*n);
    } else if (const auto elset = deck_.elsets.find(ascii_upper(fields[0])); elset != deck_.elsets.end()) {
      elements = elset->second.members;
    } else {
      fail(line, "'" + std::string(fields[0]) + "' is neither an element number nor an *ELSET defined before this line");
    }
    const std::string label = ascii_upper(fields[1]);
    for (const std::int64_t e : elements) {
      const auto element = deck_.elements.find(e);
      if (element == deck_.elements.end()) fail(line, "element " + std::to_string(e) + " is not defined before this line");
      const std::optional<ElementShape> shape = shape_of(element->second.type);
      if (!shape || shape->family == nullptr) {
        if (set.unusable.empty()) set.unusable = unusable_face(line, e, element->second.type, label);
        continue;
      }
      const auto face = label.size() == 2 && label[0] == 'S' ? field_integer(label.substr(1)) : std::nullopt;
      const std::size_t faces = shape->family->faces.size();
      if (!face || *face < 1 || static_cast<std::size_t>(*face) > faces) {
        fail(line, "'" + std::string(fields[1]) + "' is not a face of element " + std::to_string(e) + " (" +
                       element->second.type + "), whose faces are S1 to S" + std::to_string(faces));
      }
      add_members(line, face_node_count(*shape, static_cast<int>(*face)));
      set.faces.emplace_back(e, static_cast<int>(*face));
    }
  }

  /// Why a surface of a face of a beam, shell or other element is of no use to hotmesh.
  std::string unusable_face(const DeckLine& line, std::int64_t element, const std::string& type,
                            const std::string& label) const {
    const std::optional<ElementShape> shape = shape_of(type);
    return "face " + label + " of element " + std::to_string(element) + " (" + type + (shape ? ", a beam or shell" : "") +
           ") at " + place(line).text() +
           ": hotmesh takes the faces of continuum elements (CAX*, CPS*, CPE*, C3D*) only; give a *NSET of the "
           "wall's nodes instead";
  }

  InpDeck& deck_;
  const InpLimits& limits_;
  std::size_t set_members_ = 0;  ///< numbers held by all sets, face nodes included
};

/// The nodes of face `face` (1-based) of an element: its corners, and its edges' midside
/// nodes when the element is quadratic.
void face_nodes(const DeckElement& element, int face, std::vector<std::int64_t>& out) {
  const ElementShape shape = *shape_of(element.type);
  const std::vector<int>& corners = shape.family->faces[static_cast<std::size_t>(face - 1)];
  for (const int c : corners) out.push_back(element.nodes[static_cast<std::size_t>(c - 1)]);
  if (shape.nodes == shape.family->corners) return;
  for (std::size_t k = 0; k < corners.size(); ++k) {
    const int a = corners[k];
    const int b = corners[(k + 1) % corners.size()];
    if (corners.size() == 2 && k == 1) break;  // a 2D face is one edge
    for (const Edge& edge : shape.family->edges) {
      if ((edge.a == a && edge.b == b) || (edge.a == b && edge.b == a)) {
        out.push_back(element.nodes[static_cast<std::size_t>(edge.mid - 1)]);
      }
    }
  }
}

std::string names_with_sizes(const std::map<std::string, DeckSet>& sets, const InpDeck& deck) {
  std::string text;
  for (const auto& [name, set] : sets) {
    const std::string size = set.unusable.empty() ? std::to_string(deck.set_nodes(name).size()) + " nodes" : "unusable";
    text += (text.empty() ? "" : ", ") + name + " (" + size + ")";
  }
  return text.empty() ? "(none)" : text;
}

}  // namespace

std::string DeckPlace::text() const { return file.string() + ":" + std::to_string(line); }

const char* to_string(ModelKind kind) {
  switch (kind) {
    case ModelKind::axisymmetric: return "axisymmetric";
    case ModelKind::plane: return "plane";
    case ModelKind::solid: return "solid";
  }
  return "?";
}

ModelKind InpDeck::kind() const {
  std::set<ModelKind> kinds;
  std::string examples;
  for (const auto& [id, element] : elements) {
    const std::optional<ElementShape> shape = shape_of(element.type);
    if (shape && kinds.insert(shape->kind).second) {
      examples += (examples.empty() ? "" : ", ") + element.type + " (" + to_string(shape->kind) +
                  (shape->expanded ? " as ccx expands it" : "") + ", at " + element.place.text() + ")";
    }
  }
  if (kinds.empty()) {
    throw InputError::in(file.string(), "no continuum elements (CAX*, CPS*, CPE*, C3D*) nor beams, trusses, "
                                        "shells or membranes that ccx expands into 3D elements (B31, B32, T3D*, S*, "
                                        "M3D*): hotmesh reads the displacements of axisymmetric, plane or solid models");
  }
  if (kinds.size() > 1) throw InputError::in(file.string(), "elements of several kinds: " + examples + "; use one kind");
  return *kinds.begin();
}

std::vector<std::int64_t> InpDeck::set_nodes(std::string_view name) const {
  const std::string key = ascii_upper(name);
  std::vector<std::int64_t> members;
  if (const auto nset = nsets.find(key); nset != nsets.end()) {
    members = nset->second.members;
  } else if (const auto surface = surfaces.find(key); surface != surfaces.end()) {
    const DeckSet& set = surface->second;
    if (!set.unusable.empty()) {
      throw InputError::at(set.place.file.string(), set.place.line, "surface " + key + " is of no use to hotmesh: it has the " + set.unusable);
    }
    members = set.members;
    for (const auto& [element, face] : surface->second.faces) face_nodes(elements.at(element), face, members);
  } else {
    const bool elset = elsets.contains(key);
    throw InputError::in(file.string(), "no node set or surface '" + std::string(name) + "'" +
                                            (elset ? " (there is an element set of that name; give a node set or "
                                                     "a surface of element faces)"
                                                   : std::string()) +
                                            "; its node sets: " + names_with_sizes(nsets, *this) +
                                            "; its surfaces: " + names_with_sizes(surfaces, *this));
  }
  std::sort(members.begin(), members.end());
  members.erase(std::unique(members.begin(), members.end()), members.end());
  return members;
}

DeckPlace InpDeck::set_place(std::string_view name) const {
  const std::string key = ascii_upper(name);
  if (const auto nset = nsets.find(key); nset != nsets.end()) return nset->second.place;
  if (const auto surface = surfaces.find(key); surface != surfaces.end()) return surface->second.place;
  return {file, 0};
}

InpDeck read_inp(const std::filesystem::path& path, const InpLimits& limits) {
  InpDeck deck;
  deck.file = path;
  require_input_file(path);
  DeckLines files(deck, limits);  // holds the text the lines point into
  const std::vector<DeckLine> lines = files.read(path);
  DeckParser(deck, limits).parse(lines);
  return deck;
}

}  // namespace hotmesh::io
