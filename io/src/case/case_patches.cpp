// hotmesh io: the case file's patches: roles, features and periodic pairs
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

namespace {

constexpr std::array<std::string_view, 5> kPatchKeys{"role", "deflection", "partner", "angle_deg", "features"};
constexpr std::array<std::string_view, 1> kFeatureKeys{"angle"};
constexpr std::string_view kFeaturesExample = "`features: {angle: 25}` (degrees) or `features: off`";

}  // namespace

void CaseParser::read_patches(const Entry& e) {
  c_.patches_line = e.line;
  if (!reader_.map_or_empty(e, "a map of patch names to {role: ...}")) return;
  const MapEntries m = reader_.keys(e, {});
  if (m.entries.empty()) {
    reader_.error(e, "is empty; give every mesh patch a role, e.g. `wall: {role: fixed}`");
    return;
  }
  for (const Entry& patch : m.entries) read_patch(patch);
  check_periodic_pairs();
  check_tables_agree();
}

  /// Adds the patch to the case even when it has problems, so later checks can refer to it.
void CaseParser::read_patch(const Entry& e) {
  PatchSpec spec;
  spec.name = e.name;
  spec.line = e.line;
  PatchNotes& notes = notes_.emplace_back();
  const MapEntries m = reader_.map_or_empty(e, "a map {role: ...}") ? reader_.keys(e, kPatchKeys) : MapEntries{};
  if (const Entry* r = m.find("role")) {
    if (const auto text = reader_.text(*r, cat("a role (one of ", deform::kBoundaryRoleList, ")"))) {
      const std::optional<PatchRole> role = deform::kBoundaryRoleNames.parse(*text);
      notes.role_known = role.has_value();
      if (role) spec.role = *role;
      if (!notes.role_known) reader_.error(*r, cat("unknown role '", *text, "'; expected one of ", deform::kBoundaryRoleList));
    }
  } else if (e.value.IsMap() || e.value.IsNull()) {
    reader_.error(e.line, e.sub("role"), cat("missing; expected one of ", deform::kBoundaryRoleList));
  }
  const bool known = notes.role_known;
  const std::string_view role_name = to_string(spec.role);

  const Entry* deflection = m.find("deflection");
  const bool takes_table = deform::follows_shape(spec.role);
  if (deflection != nullptr && known && !takes_table) {
    reader_.error(*deflection, cat("not allowed for role ", role_name,
                                   "; only prescribed and sliding patches take a deflection table"));
  } else if (deflection != nullptr) {
    spec.deflection = read_deflection(*deflection, spec);
  } else if (known && spec.role == PatchRole::prescribed) {
    reader_.error(e.line, e.sub("deflection"), "missing; a prescribed patch needs `deflection: {file: <table.csv>}`");
  }

  if (const Entry* features = m.find("features")) {
    if (known && spec.role != PatchRole::sliding) {
      reader_.error(*features, cat("only sliding patches have features (this patch is ", role_name,
                                   "): the corners of a wall that sliding nodes hold"));
    } else {
      read_features(*features, spec.features);
    }
  }

  for (const std::string_view key : {std::string_view("partner"), std::string_view("angle_deg")}) {
    const Entry* item = m.find(key);
    if (item == nullptr) continue;
    if (known && spec.role != PatchRole::periodic) {
      reader_.error(*item, cat("only periodic patches have ", key, " (this patch is ", role_name, ")"));
    } else if (key == "partner") {
      notes.partner_line = item->line;
      spec.partner = reader_.text(*item, "the name of the other periodic patch").value_or("");
    } else {
      notes.has_angle = true;
      notes.angle_line = item->line;
      const auto valid = [](double a) { return a != 0.0 && std::abs(a) <= 180.0; };
      spec.angle_deg =
          reader_.number_where(*item, valid, "a non-zero angle in degrees with |angle_deg| <= 180").value_or(0.0);
    }
  }
  c_.patches.push_back(std::move(spec));
}

  /// `features: off | on | {angle: A}`: which corners of a sliding wall its nodes hold.
void CaseParser::read_features(const Entry& e, deform::FeatureOptions& features) {
  if (e.value.IsScalar()) {
    if (const auto on = reader_.boolean(e)) features.enabled = *on;
    return;
  }
  if (!reader_.map_or_empty(e, cat("on, off or a map {angle: <degrees>}, e.g. ", kFeaturesExample))) return;
  const MapEntries m = reader_.keys(e, kFeatureKeys);
  if (const Entry* angle = m.find("angle")) {
    const auto valid = [](double a) { return a > 0.0 && a < 180.0; };
    if (const auto degrees = reader_.number_where(*angle, valid, "an angle in degrees between 0 and 180")) {
      features.angle = *degrees * std::numbers::pi / 180.0;
    }
  }
}

std::optional<std::size_t> CaseParser::index_of(std::string_view name) const {
  const PatchSpec* p = c_.find_patch(name);
  return p == nullptr ? std::nullopt : std::optional<std::size_t>(static_cast<std::size_t>(p - c_.patches.data()));
}

bool CaseParser::periodic(std::size_t i) const {
return notes_[i].role_known && c_.patches[i].role == PatchRole::periodic;
}

  /// The periodic patch that declares patch `j` as its partner with an angle, if any.
const PatchSpec* CaseParser::declarer_of(std::size_t j) const {
  for (std::size_t k = 0; k < c_.patches.size(); ++k) {
    if (periodic(k) && notes_[k].has_angle && c_.patches[k].partner == c_.patches[j].name) return &c_.patches[k];
  }
  return nullptr;
}

  /// Each periodic pair is declared on one side (partner + angle_deg); the other side names
  /// no partner or the first one, and gives no angle. Every periodic patch is in one pair.
void CaseParser::check_periodic_pairs() {
  std::vector<std::vector<std::string>> pairs(c_.patches.size());  // partners of each patch
  std::vector<bool> reported(c_.patches.size(), false);            // a problem of its pairing was reported
  pair_periodic_patches(pairs, reported);
  require_one_partner_each(pairs, reported);
}

  /// Each pair declared by `partner:` and `angle_deg:` on one side, into the partners of both
  /// sides; every problem of a declaration reported at its key.
void CaseParser::pair_periodic_patches(std::vector<std::vector<std::string>>& pairs, std::vector<bool>& reported) {
  const std::size_t n = c_.patches.size();
  std::vector<std::string> periodic_names;
  for (std::size_t i = 0; i < n; ++i) {
    if (periodic(i)) periodic_names.push_back(c_.patches[i].name);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!periodic(i)) continue;
    const PatchSpec& p = c_.patches[i];
    const PatchNotes& pn = notes_[i];
    const auto problem = [&](std::size_t line, std::string_view sub, const std::string& message) {
      reader_.error(line, cat("patches.", p.name, sub), message);
      reported[i] = true;
    };
    if (p.partner.empty()) {  // the other side of a pair, or a partner value already reported
      if (pn.has_angle && pn.partner_line == 0) {
        problem(pn.angle_line, ".angle_deg", "needs `partner: <other periodic patch>` beside it");
      }
      reported[i] = reported[i] || pn.partner_line != 0;
      continue;
    }
    const auto j = index_of(p.partner);
    if (!j) {
      problem(pn.partner_line, ".partner",
              cat("'", p.partner, "' is not a patch of this case; periodic patches: ", join(periodic_names)));
      continue;
    }
    if (*j == i) {
      problem(pn.partner_line, ".partner", "a patch cannot be its own partner; name the other side");
      continue;
    }
    const PatchSpec& q = c_.patches[*j];
    const PatchNotes& qn = notes_[*j];
    if (!periodic(*j)) {
      reported[i] = true;  // an unknown role of q was reported already
      if (qn.role_known) {
        problem(pn.partner_line, ".partner",
                cat("'", q.name, "' has role ", to_string(q.role), "; the partner must be periodic too"));
      }
      continue;
    }
    const bool back = q.partner == p.name;
    const std::string elsewhere = cat("'", q.name, "' names '", q.partner, "' as its partner, not '", p.name, "'");
    if (pn.has_angle && qn.has_angle && back) {
      if (i > *j) {
        problem(pn.angle_line, ".angle_deg",
                cat("'", q.name, "' gives angle_deg too; give it on one side of the pair only"));
      }
      reported[i] = true;
    } else if (!q.partner.empty() && !back) {
      problem(pn.partner_line, ".partner", elsewhere);
    } else if (pn.has_angle) {
      pairs[i].push_back(q.name);
      pairs[*j].push_back(p.name);
    } else if (back && qn.has_angle) {
      continue;  // declared from the other side
    } else if (const PatchSpec* other = back ? nullptr : declarer_of(*j)) {
      problem(pn.partner_line, ".partner", cat("'", q.name, "' is already paired with '", other->name, "'"));
    } else {
      if (!back || i < *j) {
        problem(p.line, "", cat("the periodic pair ", p.name, "/", q.name,
                                " has no angle_deg; add angle_deg (the rotation from one patch to the other, "
                                "in degrees) on one side"));
      }
      reported[i] = reported[*j] = true;
    }
  }
}

  /// Every periodic patch in exactly one pair; the side without angle_deg learns its partner.
void CaseParser::require_one_partner_each(const std::vector<std::vector<std::string>>& pairs, const std::vector<bool>& reported) {
  for (std::size_t i = 0; i < c_.patches.size(); ++i) {
    if (!periodic(i)) continue;
    PatchSpec& p = c_.patches[i];
    const std::string key = "patches." + p.name;
    if (pairs[i].size() > 1) {
      reader_.error(p.line, key, cat("is in more than one periodic pair (with ", join(pairs[i]),
                                     "); each periodic patch pairs with exactly one other"));
    } else if (pairs[i].empty() && !reported[i]) {
      reader_.error(p.line, key, "periodic patch without a partner; declare the pair on one side with "
                                 "`partner: <other>` and `angle_deg: <degrees>`");
    } else if (pairs[i].size() == 1 && !notes_[i].has_angle) {
      p.partner = pairs[i][0];
    } else if (pairs[i].size() == 1 && !has_axis_) {
      reader_.error(p.line, key, cat("the periodic pair ", p.name, "/", pairs[i][0],
                                     " needs the top-level axis (the axis of the rotation), e.g. ", kAxisExample));
    }
  }
}

}  // namespace hotmesh::io::detail
