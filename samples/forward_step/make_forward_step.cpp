// hotmesh sample: a 2D channel with a forward-facing step (issue 45), made the way users make
// theirs: drawn as CAD in gmsh, the CFD mesh and the FEM mesh meshed by gmsh from that CAD, the
// metal solved by CalculiX, and one sliding patch over the whole lower wall, its sharp foot and
// its filleted shoulder included, moved by ccx's results.
//
// What it shows: a mesh from CAD has a node on every CAD vertex. The lower wall's sharp foot is
// one, and a node there cannot slide (the wall has no tangent at a corner): before issue 45 one
// sliding patch over it stalled in increment 1, Newton alternating between two residuals. Now
// the node holds the corner from the start, the others keep to their sides of it, and the one
// patch moves the mesh as the wall split at the foot into two patches does.
//
// The files (forward_step.geo draws everything; gmsh 4.8's outputs are committed as it wrote
// them, a test reruns gmsh and compares):
//   forward_step.step        the fluid's CAD: gmsh -0 forward_step.geo
//   forward_step.msh         the CFD mesh, patches wall, top, inlet, outlet (gmsh -2)
//   forward_step-split.msh   the same mesh, the wall split at the foot: floor, step (-setnumber split 1)
//   metal_gmsh.inp           the metal under the wall (-setnumber part 1 -format inp): CPS4 quads,
//                            a node set per CAD curve (Line1 ... Line4 the wall)
// and this program's (run: build/samples/forward_step/make_forward_step [--metal-gmsh FILE]
// [OUTPUT_FOLDER]; default: the committed metal_gmsh.inp, the current folder):
//   metal_mesh.inp           gmsh's metal mesh as a plane-strain model (CPE4), for *INCLUDE
//   metal.inp                the CalculiX deck: steel heated by the flow, held at its downstream end
//   forward_step.yaml        one sliding wall over the foot and the fillet, from ccx's .frd
//   forward_step-nofeatures.yaml   the same with features: off (the paper's sliding alone)
//   forward_step-split.yaml  the wall split at the foot into two sliding patches
// run.sh solves the deck with ccx and runs the three cases (docs/results/forward_step.md).
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "hotmesh/io/atomic_file.hpp"
#include "hotmesh/io/calculix.hpp"
#include "sample_generator.hpp"

#ifndef HOTMESH_FORWARD_STEP_SOURCE_DIR
#define HOTMESH_FORWARD_STEP_SOURCE_DIR "."
#endif

namespace {

namespace fs = std::filesystem;

// 1. The part, mm, as forward_step.geo draws it: the channel 60 long and 10 high, the step's
// face at x = 20 rising 3 from its sharp foot (20, 0), a fillet of radius 1 on the shoulder from
// (20, 2) to (21, 3), the metal 5 thick under the floor (its base y = -5).
constexpr double kLength = 60.0;
constexpr double kMetalBase = -5.0;

// The lower wall's CAD edges in forward_step.step, as `hotmesh cad forward_step.step` numbers
// them (the test checks it): the floor, the step's face, the fillet, the step's top.
constexpr std::string_view kFloorEdge = "1";
constexpr std::string_view kStepEdges = "2, 3, 4";

// 2. The load: the metal is heated from the gas side. At its base it is at 200 degrees C, and
// 10 K hotter per mm towards the flow: 250 at the floor, 280 on the step's top; it was drawn
// (and meshed) at 20. Held at its downstream end (x = 60: bolted there) axially and at that
// end's base corner vertically, it grows upstream and bends away from the hot side: the wall
// moves by up to 0.34 mm (at the inlet: 0.22 upstream, 0.26 down), the step's foot by 0.14 mm
// upstream and 0.11 mm down. So the step's face moves into the flow while the floor before it
// drops: the node on the foot lies on the fluid's side of the face and the metal's side of the
// floor, the load that stalled the single sliding patch before issue 45.
constexpr double kColdTemperature = 20.0;
constexpr double kBaseTemperature = 200.0;
constexpr double kTemperatureGradient = 10.0;  // K per mm in y

double metal_temperature(double y) { return kBaseTemperature + kTemperatureGradient * (y - kMetalBase); }

/// gmsh's metal mesh as a plane-strain model: its *Heading (and the line after it) left out,
/// since the deck has its own, and its plane-stress elements (CPS3, CPS4, the only ones gmsh
/// writes for surface cells) renamed plane-strain (CPE3, CPE4), which take the same nodes.
std::string plane_strain_mesh(const std::string& gmsh_text) {
  std::string out =
      "** hotmesh sample forward_step: the metal under the lower wall, meshed by gmsh 4.8 from\n"
      "** forward_step.geo (part = 1). This is gmsh's metal_gmsh.inp as a plane-strain model: its\n"
      "** CPS4 quads written as CPE4, its *Heading left to the deck. Written by make_forward_step.\n";
  std::istringstream in(gmsh_text);
  std::string line;
  bool heading = false;
  while (std::getline(in, line)) {
    if (heading) {  // the heading's text line
      heading = false;
      continue;
    }
    if (line.rfind("*Heading", 0) == 0) {
      heading = true;
      continue;
    }
    if (line.rfind("*ELEMENT", 0) == 0) {
      for (const std::string_view type : {"CPS3", "CPS4"}) {
        if (const auto at = line.find(type); at != std::string::npos) line.replace(at, type.size(), "CPE" + std::string(type.substr(3)));
      }
      if (line.find("type=CPE") == std::string::npos) {
        throw std::invalid_argument("metal_gmsh.inp: only surface cells (CPS3, CPS4) can be made plane strain, got `" + line + "`");
      }
    }
    out += line + "\n";
  }
  return out;
}

/// The node of the deck at (x, y).
std::int64_t node_at(const hotmesh::io::InpDeck& deck, double x, double y) {
  for (const auto& [id, p] : deck.nodes) {
    if (std::hypot(p.x - x, p.y - y) < 1e-9) return id;
  }
  throw std::invalid_argument(fmt::format("metal_gmsh.inp has no node at ({}, {})", x, y));
}

/// The CalculiX deck: the mesh included, the wall's node sets, steel, the supports and one
/// static step at the metal's temperatures, writing U and NT to metal.frd and printing the
/// wall's U to metal.dat.
std::string metal_deck(const hotmesh::io::InpDeck& mesh) {
  const std::int64_t last = mesh.nodes.rbegin()->first;
  if (mesh.nodes.begin()->first != 1 || static_cast<std::size_t>(last) != mesh.nodes.size()) {
    throw std::invalid_argument("metal_gmsh.inp: the nodes are not numbered 1 ... N, which NALL's GENERATE assumes");
  }
  std::string deck = fmt::format(
      "*HEADING\n"
      "forward_step: the metal under the lower wall, heated by the flow (plane strain; mm, N, MPa)\n"
      "** hotmesh sample forward_step, written by make_forward_step. Run: ccx -i metal\n"
      "*INCLUDE, INPUT=metal_mesh.inp\n"
      "** the lower wall: gmsh's node sets of its CAD curves (Line1 the floor, Line2 the step's face,\n"
      "** Line3 the fillet, Line4 the step's top); FLOOR and STEP are it split at the foot\n"
      "*NSET, NSET=WALL\nLine1, Line2, Line3, Line4\n"
      "*NSET, NSET=FLOOR\nLine1\n"
      "*NSET, NSET=STEP\nLine2, Line3, Line4\n"
      "*NSET, NSET=NALL, GENERATE\n1, {last}\n"
      "*MATERIAL, NAME=STEEL\n*ELASTIC\n2.0e5, 0.3\n*EXPANSION\n1.2e-5\n"
      "*SOLID SECTION, ELSET=METAL, MATERIAL=STEEL\n"
      "*INITIAL CONDITIONS, TYPE=TEMPERATURE\nNALL, {cold}\n"
      "** held at its downstream end: the end x = {x} (Line10) axially, its base corner ({x}, {y}) vertically\n"
      "*BOUNDARY\nLine10, 1, 1\n{corner}, 2, 2\n"
      "*STEP\n*STATIC\n"
      "** heated from the flow: {base} C at the base, {gradient} K hotter per mm towards the wall\n"
      "*TEMPERATURE\n",
      fmt::arg("last", last), fmt::arg("cold", kColdTemperature), fmt::arg("x", kLength), fmt::arg("y", kMetalBase),
      fmt::arg("corner", node_at(mesh, kLength, kMetalBase)), fmt::arg("base", kBaseTemperature),
      fmt::arg("gradient", kTemperatureGradient));
  for (const auto& [id, p] : mesh.nodes) deck += fmt::format("{}, {:.6g}\n", id, metal_temperature(p.y));
  deck += "*NODE FILE\nU, NT\n*NODE PRINT, NSET=WALL\nU\n*END STEP\n";
  return deck;
}

// 3. The cases. Inlet and outlet slip along their planes, the top is fixed (the casing is not
// in the FEM model); the wall slides over its CAD edges deflected by ccx's displacements, in
// displacement form so that the fillet stays an arc between the FEM nodes.

/// A sliding wall's entry: the node set `set` of ccx's results over CAD edges `edges`.
std::string sliding_wall(std::string_view set, std::string_view edges, std::string_view extra = "") {
  return fmt::format("{{role: sliding, deflection: {{calculix: {{frd: metal.frd, inp: metal.inp, set: {}}}, "
                     "edges: [{}], form: displacement}}{}}}",
                     set, edges, extra);
}

/// A case file; `pictures` adds close-ups of the step, its foot and fillet and the inlet.
std::string case_file(std::string_view comment, std::string_view mesh, std::string_view walls, bool pictures) {
  std::string text = fmt::format(
      "# hotmesh sample forward_step: {}\n"
      "# Written by make_forward_step. Run run.sh, or: ccx -i metal && hotmesh deform <this file>\n"
      "mesh: {}\n"
      "cad: forward_step.step      # the fluid drawn in gmsh (OpenCASCADE), its edges as hotmesh cad lists them\n"
      "length_unit: mm\n"
      "patches:\n{}"
      "  top:    {{role: fixed}}\n"
      "  inlet:  {{role: slip}}\n"
      "  outlet: {{role: slip}}\n",
      comment, mesh, walls);
  if (pictures) {
    text +=
        "pictures:\n"
        "  step:   [17, 25, -0.5, 4.5]\n"
        "  foot:   [19.5, 20.2, -0.35, 0.1]      # the sharp concave foot, (20, 0) moved to (19.86, -0.11)\n"
        "  fillet: [19.6, 21.1, 1.7, 3.1]        # the fillet, from (20, 2) to (21, 3) before the motion\n"
        "  inlet:  [0, 3, -0.6, 1.2]             # the wall's start, moved by 0.34 mm\n";
  }
  return text;
}

void write_sample(const fs::path& folder, const fs::path& metal_gmsh) {
  using hotmesh::io::write_file_atomically;
  write_file_atomically(folder / "metal_mesh.inp", plane_strain_mesh(hotmesh::io::read_file(metal_gmsh)));
  write_file_atomically(folder / "metal.inp", metal_deck(hotmesh::io::read_inp(metal_gmsh)));
  const std::string all_edges = fmt::format("{}, {}", kFloorEdge, kStepEdges);
  write_file_atomically(
      folder / "forward_step.yaml",
      case_file("one sliding wall over the step's sharp foot and\n# its filleted shoulder (issue 45)",
                "forward_step.msh", "  wall:   " + sliding_wall("WALL", all_edges) + "\n", true));
  write_file_atomically(
      folder / "forward_step-nofeatures.yaml",
      case_file("one sliding wall, features off: the paper's sliding\n# alone; the node on the foot still holds it",
                "forward_step.msh", "  wall:   " + sliding_wall("WALL", all_edges, ", features: off") + "\n", false));
  write_file_atomically(
      folder / "forward_step-split.yaml",
      case_file("the lower wall split at the step's foot into two\n# sliding patches, as the issue's user made it converge before",
                "forward_step-split.msh",
                "  floor:  " + sliding_wall("FLOOR", kFloorEdge) + "\n  step:   " + sliding_wall("STEP", kStepEdges) + "\n",
                false));
  fmt::print("forward_step: wrote metal_mesh.inp, metal.inp, forward_step.yaml, forward_step-nofeatures.yaml, "
             "forward_step-split.yaml to {}\n",
             folder.string());
}

}  // namespace

int main(int argc, char** argv) {
  fs::path metal_gmsh = fs::path(HOTMESH_FORWARD_STEP_SOURCE_DIR) / "metal_gmsh.inp";
  std::vector<char*> rest{argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (std::string_view(argv[i]) == "--metal-gmsh" && i + 1 < argc) {
      metal_gmsh = argv[++i];
    } else {
      rest.push_back(argv[i]);
    }
  }
  return hotmesh::samples::run_generator("make_forward_step", static_cast<int>(rest.size()), rest.data(),
                                         [&](const fs::path& folder) { write_sample(folder, metal_gmsh); });
}
