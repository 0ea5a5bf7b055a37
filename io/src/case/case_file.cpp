// hotmesh io: reader and validator of the case file (YAML, schema in docs/case-file.md).
// The whole file is checked before anything is returned: every problem (unknown key, wrong
// type, value out of range, missing file, bad deflection table, inconsistent patch roles or
// periodic pairs) is collected and reported in one InputError, one line per problem, as
// "<case file>:<line>: <key path>: <what is wrong, and what is expected>". The parser
// (case_parser.hpp) reads the sections; this file holds what the rest of hotmesh calls, and the
// checks of a case against its mesh. yaml-cpp stays in io/src/case; its marks are 0-based, ours
// 1-based.
#include "hotmesh/io/case_file.hpp"

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

namespace hotmesh::io {

using namespace detail;  // NOLINT: the checking vocabulary of the case file
using geometry::SampleFrame;

const PatchSpec* Case::find_patch(std::string_view name) const {
  const auto it = std::find_if(patches.begin(), patches.end(), [&](const PatchSpec& p) { return p.name == name; });
  return it == patches.end() ? nullptr : &*it;
}

std::vector<std::filesystem::path> Case::inputs() const {
  std::vector<std::filesystem::path> files{file};
  const std::vector<std::filesystem::path> mesh_files = mesh_input_files(mesh);
  files.insert(files.end(), mesh_files.begin(), mesh_files.end());
  if (cad) files.push_back(*cad);
  if (restart) files.push_back(*restart);
  for (const PatchSpec& p : patches) {
    if (!p.deflection) continue;
    const std::vector<std::filesystem::path>& read = p.deflection->files;
    for (const std::filesystem::path& f : read.empty() ? std::vector{p.deflection->file} : read) {
      if (std::find(files.begin(), files.end(), f) == files.end()) files.push_back(f);
    }
  }
  return files;
}

Case parse_case(std::string_view text, const std::filesystem::path& file) { return detail::CaseParser(file).parse(text); }

Case read_case(const std::filesystem::path& file) { return parse_case(read_file(file), file); }

void check_case_against_mesh(const Case& c, const mesh::Mesh& mesh) {
  Problems problems;
  std::vector<std::string> mesh_names;
  for (const mesh::Patch& p : mesh.patches) {
    mesh_names.push_back(p.name);
    if (c.find_patch(p.name) == nullptr) {
      problems.add(c.patches_line, "patches",
                   cat("mesh patch '", p.name, "' has no role; add `", p.name, ": {role: ...}` under patches"));
    }
  }
  const auto dimension_name = [](int d) { return d == 2 ? "2D" : "3D"; };
  for (const PatchSpec& spec : c.patches) {
    const std::string key = "patches." + spec.name;
    if (mesh.find_patch(spec.name) == nullptr) {
      problems.add(spec.line, key,
                   cat("no patch '", spec.name, "' in the mesh ", c.mesh.filename().string(), "; its patches are: ",
                       mesh_names.empty() ? std::string("(none)") : join(mesh_names)));
    }
    if (!spec.deflection) continue;
    const DeflectionSpec& d = *spec.deflection;
    if (mesh.dimension == 2 && d.mode != WallMode::automatic) {
      problems.add(d.line, key + ".deflection.mode",
                   "is for the walls of 3D meshes (a surface of revolution or CAD faces); a 2D wall is a curve");
    }
    if (mesh.dimension == 3 && !d.edges.empty()) {
      problems.add(d.line, key + ".deflection.edges",
                   "CAD edges are the walls of 2D cases (curves in the plane z = 0); a 3D wall is on CAD faces: "
                   "give them, `faces: [...]`");
    }
    if (mesh.dimension == 2 && !d.faces.empty() && !c.axis) {
      problems.add(d.line, key + ".deflection.faces",
                   cat("CAD faces are surfaces: a 2D case takes them only when it is axisymmetric, with the "
                       "top-level axis (the mesh's x, y are then z, r about it; ", kAxisExample,
                       "); a planar 2D wall is CAD edges in the plane z = 0, `edges: [...]` (hotmesh cad lists "
                       "them)"));
    }
    const SampleFrame frame = d.samples.frame;
    // 2D axisymmetric cases (an axis) take meridional tables too: (r, z) becomes (x, y) = (z, r).
    const bool axial_plane = mesh.dimension == 2 && c.axis && frame == SampleFrame::meridional;
    const int wanted = frame == SampleFrame::planar ? 2 : 3;
    if (mesh.dimension != wanted && !axial_plane) {
      problems.add(d.line, key + ".deflection",
                   cat("a ", geometry::to_string(frame), " table is for ", dimension_name(wanted),
                       " meshes but the mesh is ", dimension_name(mesh.dimension), "; give its columns as ",
                       mesh.dimension == 2 ? "x,y,dx,dy (or r,z,dr,dz in an axisymmetric case, with the axis)"
                                           : "x,y,z,dx,dy,dz or r,z,dr,dz"));
    }
  }
  if (!problems.empty()) problems.raise(c.file.string());
}

}  // namespace hotmesh::io
