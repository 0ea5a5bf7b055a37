// hotmesh io (internal): the case file's parser. One class, its sections read in files of their
// own: case_parser.cpp the top level (mesh, CAD, length unit, output, axis, restart),
// case_options.cpp the solver, material, quality and pictures, case_patches.cpp the patches'
// roles, features and periodic pairs, case_deflections.cpp their deflection tables (CSV files
// and CalculiX results) and CAD ids. Every problem is collected (problems_) and reported
// together when the whole file has been read (parse).
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "case/yaml_checks.hpp"
#include "hotmesh/io/calculix.hpp"
#include "hotmesh/io/case_file.hpp"

namespace hotmesh::io::detail {

namespace fs = std::filesystem;

inline constexpr std::string_view kAxisExample = "axis: {origin: [0, 0, 0], direction: [0, 0, 1]}";

/// What the validation learns about a patch besides its PatchSpec.
struct PatchNotes {
  bool role_known = false;
  bool has_angle = false;  ///< angle_deg given (even if its value was wrong)
  std::size_t partner_line = 0;
  std::size_t angle_line = 0;
};

class CaseParser {
 public:
  explicit CaseParser(const fs::path& file);

  Case parse(std::string_view text);

 private:
  void read_top(const Entry& root);

  fs::path resolve(const std::string& text) const;

  /// Whether an input may be a folder (a mesh in a folder of files, as OpenFOAM's polyMesh).
  enum class Folders { refused, accepted };

  /// A path that must name an existing file (or folder, if accepted).
  std::optional<fs::path> input_file(const Entry& e, std::string_view what, Folders folders = Folders::refused);

  void read_cad(const Entry& e);

  /// `output: FOLDER` or `output: {folder: FOLDER, series: true}`.
  void read_output(const Entry& e);

  void read_output_folder(const Entry& e);

  void read_axis(const Entry& e);

  void read_solver(const Entry& e);

  void read_material(const Entry& e);

  /// The limits every increment's cells keep (deform::QualityLimits).
  void read_quality(const Entry& e);

  void read_pictures(const Entry& e);

  void read_patches(const Entry& e);

  /// Adds the patch to the case even when it has problems, so later checks can refer to it.
  void read_patch(const Entry& e);

  /// `features: off | on | {angle: A}`: which corners of a sliding wall its nodes hold.
  void read_features(const Entry& e, deform::FeatureOptions& features);

  std::optional<DeflectionSpec> read_deflection(const Entry& e, const PatchSpec& patch);

  /// `calculix: {frd, inp, set, step | time}`: the table of a node set or surface of a deck,
  /// from a DISP block of its results. Each problem is reported at the key it comes from.
  bool read_calculix(const Entry& e, DeflectionSpec& spec);

  /// `step: last | N` and `time: T` of a `calculix:` map.
  bool read_step_choice(const MapEntries& m, FrdStepChoice& choice);

  /// Reads the deck and the results of a checked selection; reports each problem at its key.
  bool read_calculix_results(const Entry& e, const MapEntries& m, const CalculixSelection& selection,
                             DeflectionSpec& spec);

  /// `faces: [...]` or `edges: [...]`: numbers of CAD faces or edges (`what`), as `hotmesh cad`
  /// lists them.
  bool read_cad_ids(const Entry& e, std::string_view what, std::vector<int>& ids);

  std::optional<std::size_t> index_of(std::string_view name) const;

  bool periodic(std::size_t i) const;

  /// The periodic patch that declares patch `j` as its partner with an angle, if any.
  const PatchSpec* declarer_of(std::size_t j) const;

  /// Each periodic pair is declared on one side (partner + angle_deg); the other side names
  /// no partner or the first one, and gives no angle. Every periodic patch is in one pair.
  void check_periodic_pairs();

  /// Each pair declared by `partner:` and `angle_deg:` on one side, into the partners of both
  /// sides; every problem of a declaration reported at its key.
  void pair_periodic_patches(std::vector<std::vector<std::string>>& pairs, std::vector<bool>& reported);

  /// Every periodic patch in exactly one pair; the side without angle_deg learns its partner.
  void require_one_partner_each(const std::vector<std::vector<std::string>>& pairs, const std::vector<bool>& reported);

  /// A planar table belongs to a 2D mesh, cartesian and meridional ones to a 3D mesh; with an
  /// axis, planar and meridional tables go together too (a 2D axisymmetric case; the mesh
  /// decides, check_case_against_mesh).
  void check_tables_agree();
  Case c_;
  fs::path folder_;
  Problems problems_;
  Reader reader_;
  std::vector<PatchNotes> notes_;  ///< parallel to c_.patches
  bool has_cad_ = false;
  bool has_axis_ = false;
};

}  // namespace hotmesh::io::detail
