// hotmesh sample stator_well: FEM nodes along the metal walls, their deflections in the severe
// case, the CSV tables and the case files (see fem_tables.hpp).
#include "fem_tables.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "dimensions.hpp"

namespace hotmesh::samples::stator_well {

namespace {

constexpr double kHub = dims::kRHub * 1e-3;

/// Arc-length samples of a curve: (parameter, length from its start).
std::vector<std::array<double, 2>> arc_table(const BSplineCurve2d& curve) {
  constexpr int kSamples = 2048;
  const double a = curve.first_parameter(), b = curve.last_parameter();
  std::vector<std::array<double, 2>> table{{a, 0.0}};
  for (int i = 1; i <= kSamples; ++i) {
    const double t = i == kSamples ? b : a + (b - a) * i / kSamples;
    table.push_back({t, table.back()[1] + distance(curve.point(t), curve.point(table.back()[0]))});
  }
  return table;
}

/// Points of a curve at equal arc length, both ends included (n segments).
std::vector<Vec2> equal_arcs(const BSplineCurve2d& curve, const std::vector<std::array<double, 2>>& table, int n) {
  std::vector<Vec2> points{curve.point(curve.first_parameter())};
  std::size_t j = 0;
  for (int k = 1; k < n; ++k) {
    const double target = table.back()[1] * k / n;
    while (table[j + 1][1] < target) ++j;
    const double w = (target - table[j][1]) / (table[j + 1][1] - table[j][1]);
    points.push_back(curve.point(table[j][0] + w * (table[j + 1][0] - table[j][0])));
  }
  points.push_back(curve.point(curve.last_parameter()));
  return points;
}

bool is_rotor(Patch p) { return p != Patch::stator_front && p != Patch::fins && p != Patch::stator_rear; }

}  // namespace

Vec2 deflection(Patch patch, Vec2 zr, const SevereCase& severe) {
  const double r = zr.y;
  if (!is_rotor(patch)) return {0.0, severe.stator_growth * r / kHub};
  double dr = severe.rotor_growth * r / kHub;
  switch (patch) {
    case Patch::joint:
      if (r < (dims::kRJoint + 0.5 * dims::kJointGap) * 1e-3) dr += severe.joint_jump;
      break;
    case Patch::disc_up_lower:
    case Patch::disc_base: dr += severe.joint_jump; break;
    case Patch::disc_down: {
      const double x = std::clamp((r - 0.330) / (0.400 - 0.330), 0.0, 1.0);
      dr += severe.joint_jump * (1.0 - x * x * (3.0 - 2.0 * x));
      break;
    }
    default: break;
  }
  return {severe.axial_shift, dr};
}

const char* role(Patch p, bool sliding) {
  switch (p) {
    case Patch::inlet:
    case Patch::outlet:
    case Patch::stator_outer: return "passive";
    case Patch::casing:
    case Patch::blade: return "fixed";
    case Patch::disc_up_upper:
    case Patch::disc_up_lower:
    case Patch::disc_base:
    case Patch::disc_down: return sliding ? "sliding" : "prescribed";
    case Patch::per_lo:
    case Patch::per_hi: return "periodic";
    default: return "prescribed";
  }
}

GapChanges gap_changes(const std::vector<FemTable>& tables) {
  using namespace dims;
  const auto find = [&](Patch patch, Vec2 zr) -> const FemNode& {
    for (const FemTable& t : tables) {
      for (const FemNode& n : t.nodes) {
        if (t.patch == patch && distance(n.zr, zr) < 1e-12) return n;
      }
    }
    throw std::logic_error("stator well tables: no FEM node at the point asked for");
  };
  // The first fin's tip corner and the disc base (any of its nodes: it moves alike everywhere).
  const FemNode& tip = find(Patch::fins, at(kFinCentres[0] - 0.5 * kFinTip, kRFinTip));
  const FemNode* base = nullptr;
  for (const FemTable& t : tables) {
    if (t.patch == Patch::disc_base && !t.nodes.empty()) base = &t.nodes.front();
  }
  if (!base) throw std::logic_error("stator well tables: no disc base");
  const FemNode& b = find(Patch::joint, at(kZJointEnd, kRJoint + kJointGap));
  const FemNode& c = find(Patch::joint, at(kZJointEnd, kRJoint));
  GapChanges g;
  g.clearance_before = tip.zr.y - base->zr.y;
  g.clearance_after = tip.zr.y + tip.dzr.y - base->zr.y - base->dzr.y;
  g.joint_before = b.zr.y - c.zr.y;
  g.joint_after = b.zr.y + b.dzr.y - c.zr.y - c.dzr.y;
  return g;
}

std::vector<Patch> table_patches() {
  return {Patch::stator_front,  Patch::fins,      Patch::stator_rear, Patch::rim_up,   Patch::disc_up_upper,
          Patch::joint,         Patch::disc_up_lower, Patch::disc_base, Patch::disc_down, Patch::rim_down};
}

std::vector<FemTable> fem_tables(const std::vector<ProfileCurve>& loop, const SevereCase& severe) {
  std::vector<FemTable> tables;
  std::vector<FemNode> known;  // every node so far, to give a shared corner one id
  std::int64_t next_rotor = 1, next_stator = 5001;
  for (Patch patch : table_patches()) {
    FemTable table{patch, {}};
    for (const ProfileCurve& c : loop) {  // the patch's curves are consecutive along the loop
      if (c.patch != patch) continue;
      const auto arcs = arc_table(c.curve);
      // An odd number of elements per curve: no FEM node at a curve's middle, where the CFD
      // blocks often put one (fillet middles, symmetric distributions).
      const int n = 2 * static_cast<int>(std::ceil(0.5 * (arcs.back()[1] / severe.fem_spacing - 1.0) - 1e-9)) + 1;
      const auto points = equal_arcs(c.curve, arcs, n);
      for (std::size_t k = table.nodes.empty() ? 0 : 1; k < points.size(); ++k) {
        FemNode node{0, points[k], deflection(patch, points[k], severe)};
        const auto same = std::find_if(known.begin(), known.end(), [&](const FemNode& o) { return distance(o.zr, node.zr) < 1e-12; });
        if (same != known.end()) {
          node.id = same->id;
        } else {
          node.id = is_rotor(patch) ? next_rotor++ : next_stator++;
          known.push_back(node);
        }
        table.nodes.push_back(node);
      }
    }
    tables.push_back(std::move(table));
  }
  return tables;
}

std::string table_file(Patch patch) { return std::string(name(patch)) + ".csv"; }

std::string table_csv(const FemTable& table, const SevereCase& severe) {
  std::string csv = fmt::format(
      "# hotmesh sample stator_well: FEM deflections of '{}' in the severe case (paper section 6.2)\n"
      "# meridional table about the engine axis z, metres; written by make_stator_well\n"
      "# rotor: dz = {} m, dr = {} m * r / {} m; lower disc component: dr + {} m; stator: dz = 0, dr = {} m * r / {} m\n"
      "id,r,z,dr,dz\n",
      name(table.patch), severe.axial_shift, severe.rotor_growth, kHub, severe.joint_jump, severe.stator_growth, kHub);
  for (const FemNode& n : table.nodes) csv += fmt::format("{},{:.10g},{:.10g},{:.10g},{:.10g}\n", n.id, n.zr.y, n.zr.x, n.dzr.y, n.dzr.x);
  return csv;
}

std::string case_file_name(const std::string& label, bool sliding) {
  return "case_" + label + (sliding ? "" : "_nosliding") + ".yaml";
}

std::string case_file(const std::vector<ProfileCurve>& loop, const std::string& label, bool sliding) {
  std::string text = fmt::format(
      "# hotmesh sample: the turbine stator well of the paper's section 6, sliding option {}.\n"
      "# A 3.6 degree sector of the interstage cavity: the rotor moves axially and grows radially,\n"
      "# the seal clearance closes by about 60 % and the lower disc component moves radially\n"
      "# against the upper one at the joint (Figs. 13-17).\n"
      "# {}\n"
      "# Written by make_stator_well (see samples/stator_well/README.md). From this folder, run\n"
      "#     hotmesh deform {}\n"
      "mesh: {}\n"
      "cad: {}\n"
      "axis: {{origin: [0, 0, 0], direction: [0, 0, 1]}}\n"
      "solver: {{increments: 16}}\n"
      "patches:\n",
      sliding ? "on" : "off",
      sliding ? "The disc faces and the disc base slide over their deflected CAD curves."
              : "Every metal wall follows its FEM deflection exactly.",
      case_file_name(label, sliding), kMeshFile, kCadFile);
  const auto tables = table_patches();
  for (int p = 0; p < kPatchCount; ++p) {
    const auto patch = static_cast<Patch>(p);
    std::string entry = fmt::format("  {}: {{role: {}", name(patch), role(patch, sliding));
    if (std::find(tables.begin(), tables.end(), patch) != tables.end()) {
      entry += fmt::format(", deflection: {{file: {}, faces: [{}], form: displacement}}", table_file(patch),
                           fmt::join(cad_faces(loop, patch), ", "));
    }
    if (patch == Patch::per_lo) entry += fmt::format(", partner: per_hi, angle_deg: {}", kSectorDegrees);
    text += entry + "}\n";
  }
  return text;
}

std::string engine_case_file_name(const std::string& label, const std::string& format) {
  return "case_" + label + "_" + format + ".yaml";
}

std::string engine_case_file(const std::vector<ProfileCurve>& loop, const std::string& label, const std::string& format,
                             const std::string& mesh) {
  std::string text = case_file(loop, label, true);
  const auto replace = [&](const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    if (at == std::string::npos) throw std::logic_error("case file without '" + from + "'");
    text.replace(at, from.size(), to);
  };
  replace("hotmesh deform " + case_file_name(label, true), "hotmesh deform " + engine_case_file_name(label, format));
  replace(std::string("mesh: ") + kMeshFile, "mesh: " + mesh);
  replace("# Written by make_stator_well",
          "# The mesh " + mesh + " is the .msh file's sector (written by make_stator_well --engine-formats FOLDER).\n"
          "# Written by make_stator_well");
  return text;
}

}  // namespace hotmesh::samples::stator_well
