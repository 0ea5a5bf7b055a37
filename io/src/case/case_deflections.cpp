// hotmesh io: the case file's deflection tables: a CSV file or CalculiX results
// (a node set of a deck, a step of its .frd), the reconstruction's options, CAD faces and edges
// (case_parser.hpp).
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <stdexcept>
#include <system_error>
#include <type_traits>
#include <utility>

#include "hotmesh/core/input_error.hpp"
#include "hotmesh/geometry/reconstruction.hpp"
#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/deflection_csv.hpp"
#include "hotmesh/io/mesh_files.hpp"
#include "case/case_parser.hpp"

namespace hotmesh::io::detail {

using geometry::SampleFrame;

namespace {

constexpr std::array<std::string_view, 7> kDeflectionKeys{"file", "calculix", "degree", "faces", "edges", "form", "mode"};
constexpr std::array<std::string_view, 5> kCalculixKeys{"frd", "inp", "set", "step", "time"};
constexpr std::string_view kCalculixExample = "`calculix: {frd: disc.frd, inp: disc.inp, set: DISC_FACE}`";

}  // namespace

std::optional<DeflectionSpec> CaseParser::read_deflection(const Entry& e, const PatchSpec& patch) {
  if (!reader_.map_or_empty(e, "a map {file: <table.csv>, degree: <1..5>, faces: [...]}")) return std::nullopt;
  const MapEntries m = reader_.keys(e, kDeflectionKeys);
  DeflectionSpec spec;
  spec.line = e.line;
  bool table_read = false;
  const Entry* file = m.find("file");
  const Entry* calculix = m.find("calculix");
  if (file != nullptr && calculix != nullptr) {
    reader_.error(*calculix, "give either `file:` (a CSV table) or `calculix:` (CalculiX results), not both");
  } else if (calculix != nullptr) {
    table_read = read_calculix(*calculix, spec);
  } else if (file == nullptr) {
    reader_.error(e.line, e.sub("file"), cat("missing; give the deflection table, e.g. `file: deflections.csv`, "
                                             "or CalculiX results, e.g. ", kCalculixExample));
  } else if (auto path = input_file(*file, "the deflection table file name (.csv)")) {
    spec.file = *path;
    spec.files = {*path};
    try {
      spec.samples = parse_deflection_csv(read_file(*path), path->string());
      table_read = true;
    } catch (const InputError& error) {
      reader_.error(*file, error.what());
    }
  }
  const Entry& source = file != nullptr ? *file : (calculix != nullptr ? *calculix : e);
  bool ok = table_read;
  const Entry* degree = m.find("degree");
  if (degree != nullptr) {
    const auto value = reader_.integer_in(*degree, 1, geometry::kMaxReconstructionDegree);
    ok = ok && value.has_value();
    spec.degree = value.value_or(spec.degree);
  }
  if (ok && spec.samples.size() < static_cast<std::size_t>(spec.degree) + 1) {
    reader_.error(degree != nullptr ? *degree : source,
                  cat("a degree-", std::to_string(spec.degree), " curve needs at least ",
                      std::to_string(spec.degree + 1), " samples, the table has ",
                      std::to_string(spec.samples.size())));
    ok = false;
  }
  const Entry* faces = m.find("faces");
  const Entry* edges = m.find("edges");
  if (faces != nullptr) ok = read_cad_ids(*faces, "face", spec.faces) && ok;
  if (edges != nullptr) ok = read_cad_ids(*edges, "edge", spec.edges) && ok;
  if (faces != nullptr && edges != nullptr) {
    reader_.error(*edges, "give either `faces:` (CAD faces: 3D walls, or an axisymmetric 2D case's) or `edges:` "
                          "(CAD edges in the plane of a 2D case), not both");
    ok = false;
  }
  if (const Entry* form = m.find("form")) {
    const auto value = reader_.choice(*form, geometry::kDeflectionFormNames);
    ok = ok && value.has_value();
    if (value) spec.form = *value;
  }
  if (const Entry* mode = m.find("mode")) {
    const auto value = reader_.choice(*mode, kWallModeNames);
    ok = ok && value.has_value();
    if (value) spec.mode = *value;
    if (value == WallMode::meridional && !has_axis_) {
      reader_.error(*mode, cat("a meridional wall is a surface of revolution about the top-level axis; give it, "
                               "e.g. ",
                               kAxisExample));
      ok = false;
    }
  }

  if (table_read && spec.samples.frame == SampleFrame::meridional && !has_axis_) {
    reader_.error(patch.line, "patches." + patch.name,
                  cat("its deflection table is meridional (r, z), which needs the top-level axis, e.g. ",
                      kAxisExample));
  }
  if (!ok) return std::nullopt;
  return spec;
}

  /// `calculix: {frd, inp, set, step | time}`: the table of a node set or surface of a deck,
  /// from a DISP block of its results. Each problem is reported at the key it comes from.
bool CaseParser::read_calculix(const Entry& e, DeflectionSpec& spec) {
  if (!reader_.map_or_empty(e, cat("a map such as ", kCalculixExample))) return false;
  const MapEntries m = reader_.keys(e, kCalculixKeys);
  CalculixSelection selection;
  bool ok = true;
  const auto required = [&](std::string_view key, std::string_view what) -> const Entry* {
    const Entry* x = m.find(key);
    if (x == nullptr) reader_.error(e.line, e.sub(key), cat("missing; give ", what, ", e.g. ", kCalculixExample));
    ok = ok && x != nullptr;
    return x;
  };
  const Entry* frd = required("frd", "the results file ccx wrote (.frd)");
  const Entry* inp = required("inp", "the input deck ccx solved (.inp), which defines the set");
  const Entry* set = required("set", "a node set (*NSET) or surface (*SURFACE) of the deck");
  if (frd != nullptr) {
    const auto path = input_file(*frd, "the CalculiX results file (.frd)");
    ok = ok && path.has_value();
    selection.frd = path.value_or(fs::path());
  }
  if (inp != nullptr) {
    const auto path = input_file(*inp, "the CalculiX input deck (.inp)");
    ok = ok && path.has_value();
    selection.inp = path.value_or(fs::path());
  }
  if (set != nullptr) {
    const auto name = reader_.text(*set, "the name of a node set or surface of the deck");
    ok = ok && name.has_value();
    selection.set = name.value_or("");
  }
  ok = read_step_choice(m, selection.choice) && ok;
  if (!ok) return false;
  return read_calculix_results(e, m, selection, spec);
}

  /// `step: last | N` and `time: T` of a `calculix:` map.
bool CaseParser::read_step_choice(const MapEntries& m, FrdStepChoice& choice) {
  bool ok = true;
  const Entry* step = m.find("step");
  if (step != nullptr && !(step->value.IsScalar() && step->value.Scalar() == "last")) {
    const auto n = step->value.IsScalar() && !quoted(step->value) ? detail::parse<std::int64_t>(step->value.Scalar())
                                                                   : std::nullopt;
    if (!n || *n < 1 || *n > INT_MAX) {
      reader_.error(*step, "expected `last` or the number of an analysis step (*STEP, from 1), got " +
                               describe(step->value));
      ok = false;
    } else {
      choice.step = static_cast<int>(*n);
    }
  }
  if (const Entry* time = m.find("time")) {
    choice.time = reader_.number(*time);
    ok = ok && choice.time.has_value();
  }
  return ok;
}

  /// Reads the deck and the results of a checked selection; reports each problem at its key.
bool CaseParser::read_calculix_results(const Entry& e, const MapEntries& m, const CalculixSelection& selection,
                                       DeflectionSpec& spec) {
  const auto attempt = [&](const Entry& at, const auto& work) {
    try {
      work();
      return true;
    } catch (const InputError& error) {
      reader_.error(at, error.what());
      return false;
    }
  };
  InpDeck deck;
  FrdResults results;
  if (!attempt(*m.find("inp"), [&] { deck = read_inp(selection.inp); })) return false;
  if (!attempt(*m.find("set"), [&] { deck.set_nodes(selection.set); })) return false;
  if (!attempt(*m.find("frd"), [&] { results = read_frd(selection.frd); })) return false;
  const Entry* step = m.find("step");
  const Entry* time = m.find("time");
  const Entry& choice_at = step != nullptr ? *step : (time != nullptr ? *time : *m.find("frd"));
  if (!attempt(choice_at, [&] { choose_displacements(results, selection.choice); })) return false;
  return attempt(e, [&] {
    CalculixTable table = calculix_table(results, deck, selection);
    spec.file = selection.frd;
    spec.files = table.files;
    spec.samples = std::move(table.samples);
    spec.calculix = CalculixNote{selection, table.kind, table.step, table.time, table.min_temperature,
                                 table.max_temperature};
  });
}

  /// `faces: [...]` or `edges: [...]`: numbers of CAD faces or edges (`what`), as `hotmesh cad`
  /// lists them.
bool CaseParser::read_cad_ids(const Entry& e, std::string_view what, std::vector<int>& ids) {
  if (!e.value.IsSequence() || e.value.size() == 0) {
    const std::string got = e.value.IsSequence() ? "an empty list" : describe(e.value);
    reader_.error(e, cat("expected a list of CAD ", what, " numbers (>= 1), e.g. [3, 4], got ", got));
    return false;
  }
  bool ok = true;
  for (std::size_t i = 0; i < e.value.size(); ++i) {
    const Entry entry = e.item(i);
    const auto id = reader_.integer_in(entry, 1);
    if (id && std::find(ids.begin(), ids.end(), *id) != ids.end()) {
      reader_.error(entry, cat(what, " ", std::to_string(*id), " is listed twice"));
    } else if (id) {
      ids.push_back(*id);
      continue;
    }
    ok = false;
  }
  if (!has_cad_) {
    reader_.error(e, cat("CAD ", what, " numbers need a CAD file; add `cad: <file.step>` at the top level"));
    ok = false;
  }
  return ok;
}

  /// A planar table belongs to a 2D mesh, cartesian and meridional ones to a 3D mesh; with an
  /// axis, planar and meridional tables go together too (a 2D axisymmetric case; the mesh
  /// decides, check_case_against_mesh).
void CaseParser::check_tables_agree() {
  const PatchSpec* first = nullptr;
  for (const PatchSpec& p : c_.patches) {
    if (!p.deflection) continue;
    if (first == nullptr) first = &p;
    const SampleFrame mine = p.deflection->samples.frame;
    const SampleFrame theirs = first->deflection->samples.frame;
    const bool axisymmetric_2d = has_axis_ && mine != SampleFrame::cartesian && theirs != SampleFrame::cartesian;
    if ((mine == SampleFrame::planar) != (theirs == SampleFrame::planar) && !axisymmetric_2d) {
      reader_.error(p.deflection->line, cat("patches.", p.name, ".deflection"),
                    cat("its table is ", geometry::to_string(mine), " but the table of patch '", first->name,
                        "' (line ", std::to_string(first->deflection->line), ") is ", geometry::to_string(theirs),
                        "; planar tables are for 2D meshes, the others for 3D meshes"));
    }
  }
}

}  // namespace hotmesh::io::detail
