// hotmesh deform: the boundary roles of mesh patches and what each role means, in one table of
// traits beside the enum: its name (case file, report.json, restart files), the code its nodes
// carry in the output, how strong it is where patches meet, and whether it follows a shape.
// Header-only, for io and app as for the solver: read the table, do not restate it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "hotmesh/core/enum_names.hpp"

namespace hotmesh::deform {

enum class BoundaryRole : std::uint8_t {
  fixed,       ///< u = 0
  prescribed,  ///< follows its deflected shape: a node at parameter t moves with c_lambda(t)
  slip,        ///< u . n = 0 on the original planar boundary (eq. 11)
  sliding,     ///< slides over its deflected shape (section 4)
  passive,     ///< displacement from a surface-only spring solve (section 6.1)
  periodic,    ///< u_slave = R u_master with its partner patch
};

/// Node roles as stored per node for output: 0 for interior nodes, else the node_code of the
/// role (BoundaryRoleTraits).
using NodeRoleCode = std::uint8_t;
/// The code of a node on no patch.
inline constexpr NodeRoleCode kInteriorNodeCode = 0;

/// What a role means.
struct BoundaryRoleTraits {
  BoundaryRole role;
  /// The name the case file, report.json and restart files use.
  std::string_view name;
  /// Its nodes' code in MotionResult::node_roles and the output's node role field.
  NodeRoleCode node_code;
  /// A node on patches of several roles takes the strongest (boundary_conditions.hpp):
  ///     fixed > prescribed > sliding > passive > slip > periodic > interior (0),
  /// so it is never moved twice.
  int strength;
  /// Moves with a deflected shape (PatchMotion::shape, required): prescribed follows it, sliding
  /// slides over it. Only these roles take a deflection table or CAD faces, and their walls are
  /// the ones measured against the shape (wall gaps, wall deviations) and the moving walls the
  /// stiffening by distance is taken from.
  bool follows_shape;
};

/// Every role, in the enum's order.
inline constexpr std::array<BoundaryRoleTraits, 6> kBoundaryRoleTraits{{
    {BoundaryRole::fixed, "fixed", 1, 6, false},
    {BoundaryRole::prescribed, "prescribed", 2, 5, true},
    {BoundaryRole::slip, "slip", 3, 2, false},
    {BoundaryRole::sliding, "sliding", 4, 4, true},
    {BoundaryRole::passive, "passive", 5, 3, false},
    {BoundaryRole::periodic, "periodic", 6, 1, false},
}};

/// The traits of `role`; null for a value outside the enum (a damaged or cast value).
constexpr const BoundaryRoleTraits* find_traits(BoundaryRole role) {
  for (const BoundaryRoleTraits& t : kBoundaryRoleTraits) {
    if (t.role == role) return &t;
  }
  return nullptr;
}

/// Whether patches of this role move with a deflected shape (prescribed, sliding).
constexpr bool follows_shape(BoundaryRole role) {
  const BoundaryRoleTraits* t = find_traits(role);
  return t != nullptr && t->follows_shape;
}

/// How strong the role is where patches meet (BoundaryRoleTraits::strength); 0 outside the enum.
constexpr int role_strength(BoundaryRole role) {
  const BoundaryRoleTraits* t = find_traits(role);
  return t != nullptr ? t->strength : 0;
}

/// The code of a node with this role (MotionResult::node_roles).
constexpr NodeRoleCode node_role_code(BoundaryRole role) {
  const BoundaryRoleTraits* t = find_traits(role);
  return t != nullptr ? t->node_code : kInteriorNodeCode;
}

/// The role of a node's code, which is not kInteriorNodeCode.
constexpr BoundaryRole role_of_node_code(NodeRoleCode code) {
  for (const BoundaryRoleTraits& t : kBoundaryRoleTraits) {
    if (t.node_code == code) return t.role;
  }
  return static_cast<BoundaryRole>(code - 1);  // outside the table: the value it would have
}

/// The names the case file, report.json and restart files use (to_string, and the parsers).
inline constexpr EnumNames<BoundaryRole, kBoundaryRoleTraits.size()> kBoundaryRoleNames = [] {
  EnumNames<BoundaryRole, kBoundaryRoleTraits.size()> names{};
  for (std::size_t i = 0; i < kBoundaryRoleTraits.size(); ++i) {
    names.entries[i] = {kBoundaryRoleTraits[i].role, kBoundaryRoleTraits[i].name};
  }
  return names;
}();
constexpr std::string_view to_string(BoundaryRole role) { return kBoundaryRoleNames.name(role); }

namespace role_names_detail {
constexpr std::size_t joined_length() {
  std::size_t length = 0;
  for (const BoundaryRoleTraits& t : kBoundaryRoleTraits) length += t.name.size() + 2;
  return length - 2;
}
constexpr std::array<char, joined_length()> join() {
  std::array<char, joined_length()> text{};
  std::size_t k = 0;
  for (const BoundaryRoleTraits& t : kBoundaryRoleTraits) {
    if (k > 0) {
      text[k++] = ',';
      text[k++] = ' ';
    }
    for (const char c : t.name) text[k++] = c;
  }
  return text;
}
inline constexpr std::array<char, joined_length()> kJoined = join();
}  // namespace role_names_detail

/// Every role's name, in the table's order, for messages: "fixed, prescribed, slip, sliding,
/// passive, periodic".
inline constexpr std::string_view kBoundaryRoleList{role_names_detail::kJoined.data(), role_names_detail::kJoined.size()};

static_assert([] {
  for (std::size_t i = 0; i < kBoundaryRoleTraits.size(); ++i) {
    const BoundaryRoleTraits& t = kBoundaryRoleTraits[i];
    if (static_cast<std::size_t>(t.role) != i || static_cast<std::size_t>(t.node_code) != 1 + i) return false;
  }
  return true;
}(), "kBoundaryRoleTraits: one entry per role, in the enum's order, node codes 1 + the enum");
static_assert(kBoundaryRoleList == "fixed, prescribed, slip, sliding, passive, periodic");

}  // namespace hotmesh::deform
