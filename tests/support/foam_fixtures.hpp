// hotmesh tests: small OpenFOAM polyMesh folders written in code, in every form the reader
// takes (ASCII or binary, label 32/64 bit, scalar 32/64 bit, faceList or faceCompactList,
// plain or gzipped), and blockMesh run on a case folder.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <zlib.h>

#include "hotmesh/core/vec3.hpp"
#include "run_command.hpp"
#include "test_support.hpp"

namespace hotmesh::test::foam {

struct PatchEntry {
  std::string name, type;
  int start = 0, count = 0;
};

struct PolyMeshData {
  std::vector<geometry::Vec3> points;
  std::vector<std::vector<std::int64_t>> faces;
  std::vector<std::int64_t> owner, neighbour;
  std::vector<PatchEntry> patches;
};

/// The 2 x 1 x 1 block [0,2]x[0,1]x[0,1] of two unit cubes, as blockMesh writes it (points,
/// faces, owner, neighbour copied from its output): patches inlet (x = 0), outlet (x = 2),
/// walls (the other eight faces).
inline PolyMeshData block_2x1x1() {
  PolyMeshData m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0},
              {0, 0, 1}, {1, 0, 1}, {2, 0, 1}, {0, 1, 1}, {1, 1, 1}, {2, 1, 1}};
  m.faces = {{1, 4, 10, 7},  {0, 6, 9, 3}, {2, 5, 11, 8}, {0, 1, 7, 6},  {1, 2, 8, 7},  {3, 9, 10, 4},
             {4, 10, 11, 5}, {0, 3, 4, 1}, {1, 4, 5, 2},  {6, 7, 10, 9}, {7, 8, 11, 10}};
  m.owner = {0, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1};
  m.neighbour = {1};
  m.patches = {{"inlet", "patch", 1, 1}, {"outlet", "patch", 2, 1}, {"walls", "wall", 3, 8}};
  return m;
}

/// One prism (a triangle 0-1-2 at z = 0 extruded to 3-4-5 at z = 1), all faces on "walls".
inline PolyMeshData one_prism() {
  PolyMeshData m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  m.faces = {{0, 2, 1}, {3, 4, 5}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}};
  m.owner = {0, 0, 0, 0, 0};
  m.patches = {{"walls", "wall", 0, 5}};
  return m;
}

/// One tetrahedron (0, 1, 2 at z = 0, 3 above 0), all faces on "walls".
inline PolyMeshData one_tetrahedron() {
  PolyMeshData m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  m.owner = {0, 0, 0, 0};
  m.patches = {{"walls", "wall", 0, 4}};
  return m;
}

/// One pyramid (the unit square 0-1-2-3 at z = 0, apex 4 above its centre), patches "base"
/// (the square) and "sides" (the four triangles).
inline PolyMeshData one_pyramid() {
  PolyMeshData m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 0.8}};
  m.faces = {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  m.owner = {0, 0, 0, 0, 0};
  m.patches = {{"base", "wall", 0, 1}, {"sides", "wall", 1, 4}};
  return m;
}

/// The unit cube with its top split into two triangles: a polyhedron of 7 faces, no hexahedron.
inline PolyMeshData split_top_cube() {
  PolyMeshData m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  m.faces = {{0, 3, 2, 1}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  m.owner = {0, 0, 0, 0, 0, 0, 0};
  m.patches = {{"walls", "wall", 0, 7}};
  return m;
}

struct Layout {
  bool binary = false;
  bool gzip = false;
  int label_bits = 32;
  int scalar_bits = 64;
  bool compact_faces = false;  ///< faceCompactList instead of faceList
};

inline std::string foam_header(const Layout& layout, const std::string& class_name, const std::string& object) {
  return fmt::format(
      "/*--------------------------------*- C++ -*----------------------------------*\\\n"
      "  written by hotmesh's tests\n"
      "\\*---------------------------------------------------------------------------*/\n"
      "FoamFile\n{{\n    version     2.0;\n    format      {};\n    arch        \"LSB;label={};scalar={}\";\n"
      "    class       {};\n    location    \"constant/polyMesh\";\n    object      {};\n}}\n"
      "// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n\n",
      layout.binary ? "binary" : "ascii", layout.label_bits, layout.scalar_bits, class_name, object);
}

inline void append_label(std::string& out, std::int64_t value, const Layout& layout) {
  if (layout.label_bits == 32) {
    const auto v = static_cast<std::int32_t>(value);
    out.append(reinterpret_cast<const char*>(&v), 4);
  } else {
    out.append(reinterpret_cast<const char*>(&value), 8);
  }
}

inline std::string label_list(const std::vector<std::int64_t>& labels, const Layout& layout) {
  std::string out = fmt::format("{}\n(", labels.size());
  if (layout.binary) {
    for (const std::int64_t l : labels) append_label(out, l, layout);
  } else {
    for (const std::int64_t l : labels) out += fmt::format("\n{}", l);
    out += "\n";
  }
  return out + ")\n";
}

inline std::string points_list(const std::vector<geometry::Vec3>& points, const Layout& layout) {
  std::string out = fmt::format("{}\n(", points.size());
  for (const auto& p : points) {
    if (!layout.binary) {
      out += fmt::format("\n({} {} {})", p.x, p.y, p.z);
      continue;
    }
    for (const double c : {p.x, p.y, p.z}) {
      if (layout.scalar_bits == 32) {
        const auto f = static_cast<float>(c);
        out.append(reinterpret_cast<const char*>(&f), 4);
      } else {
        out.append(reinterpret_cast<const char*>(&c), 8);
      }
    }
  }
  return out + (layout.binary ? ")\n" : "\n)\n");
}

inline std::string faces_list(const PolyMeshData& m, const Layout& layout) {
  if (layout.compact_faces) {
    std::vector<std::int64_t> offsets{0}, nodes;
    for (const auto& f : m.faces) {
      nodes.insert(nodes.end(), f.begin(), f.end());
      offsets.push_back(static_cast<std::int64_t>(nodes.size()));
    }
    return label_list(offsets, layout) + "\n" + label_list(nodes, layout);
  }
  std::string out = fmt::format("{}\n(\n", m.faces.size());
  for (const auto& f : m.faces) {
    if (layout.binary) {
      out += fmt::format("{}(", f.size());
      for (const std::int64_t l : f) append_label(out, l, layout);
      out += ")\n";
    } else {
      out += fmt::format("{}({})\n", f.size(), fmt::join(f, " "));
    }
  }
  return out + ")\n";
}

inline std::string boundary_list(const PolyMeshData& m) {
  std::string out = fmt::format("{}\n(\n", m.patches.size());
  for (const auto& p : m.patches) {
    out += fmt::format(
        "    {}\n    {{\n        type            {};\n        inGroups        List<word> 1({});\n"
        "        nFaces          {};\n        startFace       {};\n    }}\n",
        p.name, p.type, p.type, p.count, p.start);
  }
  return out + ")\n";
}

inline std::string gzipped(const std::string& text) {
  uLongf size = compressBound(static_cast<uLong>(text.size())) + 32;
  std::string out(size, '\0');
  z_stream z{};
  deflateInit2(&z, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY);
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  z.avail_in = static_cast<uInt>(text.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  deflate(&z, Z_FINISH);
  out.resize(out.size() - z.avail_out);
  deflateEnd(&z);
  return out;
}

inline std::string gunzipped(const std::string& data) {
  std::string out(64 * data.size() + 1024, '\0');
  z_stream z{};
  inflateInit2(&z, 15 + 32);
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  z.avail_in = static_cast<uInt>(data.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  inflate(&z, Z_FINISH);
  out.resize(out.size() - z.avail_out);
  inflateEnd(&z);
  return out;
}

inline void write_foam_file(const std::filesystem::path& folder, const std::string& name, const std::string& text,
                            const Layout& layout) {
  if (layout.gzip) {
    write_text(folder / (name + ".gz"), gzipped(text));
  } else {
    write_text(folder / name, text);
  }
}

/// Writes the polyMesh files of `m` into `folder` (created).
inline void write_poly_mesh(const std::filesystem::path& folder, const PolyMeshData& m, const Layout& layout = {}) {
  std::filesystem::create_directories(folder);
  const std::string tail = "\n// ************************************************************************* //\n";
  write_foam_file(folder, "points", foam_header(layout, "vectorField", "points") + points_list(m.points, layout) + tail,
                  layout);
  write_foam_file(folder, "faces",
                  foam_header(layout, layout.compact_faces ? "faceCompactList" : "faceList", "faces") +
                      faces_list(m, layout) + tail,
                  layout);
  write_foam_file(folder, "owner", foam_header(layout, "labelList", "owner") + label_list(m.owner, layout) + tail,
                  layout);
  write_foam_file(folder, "neighbour",
                  foam_header(layout, "labelList", "neighbour") + label_list(m.neighbour, layout) + tail, layout);
  Layout ascii = layout;
  ascii.binary = false;  // OpenFOAM writes the boundary dictionary as text in either format
  write_foam_file(folder, "boundary", foam_header(layout, "polyBoundaryMesh", "boundary") + boundary_list(m) + tail,
                  ascii);
}

/// blockMesh (Debian's OpenFOAM), or an empty string if it is not installed.
inline std::string block_mesh_command() {
  if (!std::filesystem::exists("/usr/bin/blockMesh")) return {};
  // Debian's OpenFOAM finds its etc/ folder through WM_PROJECT_DIR.
  const char* dir = std::getenv("WM_PROJECT_DIR");
  return dir ? "blockMesh" : "WM_PROJECT_DIR=/usr/share/openfoam blockMesh";
}
/// gmshToFoam (Debian's OpenFOAM), or an empty string if it is not installed.
inline std::string gmsh_to_foam_command() {
  if (!std::filesystem::exists("/usr/bin/gmshToFoam")) return {};
  const char* dir = std::getenv("WM_PROJECT_DIR");
  return dir ? "gmshToFoam" : "WM_PROJECT_DIR=/usr/share/openfoam gmshToFoam";
}
/// The ramp channel 2h x h (h = 1), 21 x 12 cells graded towards the lower wall, 0.05 thick.
inline constexpr const char* kRampChannel = R"(
vertices ((0 0 0) (2 0 0) (2 1 0) (0 1 0) (0 0 0.05) (2 0 0.05) (2 1 0.05) (0 1 0.05));
blocks (hex (0 1 2 3 4 5 6 7) (21 12 1) simpleGrading (1 20 1));
boundary (
  left {type patch; faces ((0 4 7 3));}
  right {type patch; faces ((1 2 6 5));}
  bottom {type wall; faces ((0 1 5 4));}
  top {type wall; faces ((3 7 6 2));}
  frontAndBack {type empty; faces ((0 3 2 1) (4 5 6 7));}
);
)";

inline std::string check_mesh_command() {
  const char* dir = std::getenv("WM_PROJECT_DIR");
  return dir ? "checkMesh" : "WM_PROJECT_DIR=/usr/share/openfoam checkMesh";
}

/// A case folder with system/controlDict, fvSchemes, fvSolution and blockMeshDict (`dict`: the part after the
/// header); writeFormat ascii with 17 digits or binary.
inline void write_block_mesh_case(const std::filesystem::path& folder, const std::string& dict, bool binary = false) {
  std::filesystem::create_directories(folder / "system");
  std::filesystem::create_directories(folder / "constant");
  write_text(folder / "system" / "controlDict",
             fmt::format("FoamFile {{ version 2.0; format ascii; class dictionary; object controlDict; }}\n"
                         "application blockMesh; startFrom startTime; startTime 0; stopAt endTime; endTime 1;\n"
                         "deltaT 1; writeControl timeStep; writeInterval 1; writeFormat {};\n"
                         "writePrecision 17; writeCompression off; timeFormat general; timePrecision 6;\n",
                         binary ? "binary" : "ascii"));
  // What checkMesh reads besides the mesh.
  write_text(folder / "system" / "fvSchemes",
             "FoamFile { version 2.0; format ascii; class dictionary; object fvSchemes; }\n"
             "ddtSchemes { default Euler; } gradSchemes { default Gauss linear; } divSchemes { default none; }\n"
             "laplacianSchemes { default Gauss linear corrected; } interpolationSchemes { default linear; }\n"
             "snGradSchemes { default corrected; }\n");
  write_text(folder / "system" / "fvSolution",
             "FoamFile { version 2.0; format ascii; class dictionary; object fvSolution; }\nsolvers { }\n");
  write_text(folder / "system" / "blockMeshDict",
             "FoamFile { version 2.0; format ascii; class dictionary; object blockMeshDict; }\n" + dict);
}

/// Runs blockMesh on a case folder; the output if it failed.
inline CommandResult run_block_mesh(const std::filesystem::path& folder) {
  return run_command(block_mesh_command() + " -case " + shell_quote(folder.string()));
}

/// checkMesh on `polymesh`, copied with the system folder of the case `cfd` into a new case `check`.
inline CommandResult check_mesh(const std::filesystem::path& cfd, const std::filesystem::path& polymesh,
                                const std::filesystem::path& check) {
  std::filesystem::create_directories(check / "constant");
  std::filesystem::copy(cfd / "system", check / "system", std::filesystem::copy_options::recursive);
  std::filesystem::copy(polymesh, check / "constant" / "polyMesh");
  return run_command(check_mesh_command() + " -case " + shell_quote(check.string()));
}

/// snappyHexMesh (Debian's OpenFOAM), or an empty string if it is not installed.
inline std::string snappy_hex_mesh_command() {
  if (!std::filesystem::exists("/usr/bin/snappyHexMesh")) return {};
  const char* dir = std::getenv("WM_PROJECT_DIR");
  return dir ? "snappyHexMesh" : "WM_PROJECT_DIR=/usr/share/openfoam snappyHexMesh";
}

/// A box [-1, 1]^3 of 8^3 cells (patch `box`) around a ball of radius 0.45 (patch `ball`),
/// each cell cut by the ball refined once, snapped: snappyHexMesh's split hexahedra (its
/// polyhedra, 248 of 864 cells), as the flange tutorial has them, in about 2 s.
inline constexpr const char* kBallInBox = R"(
vertices ((-1 -1 -1) (1 -1 -1) (1 1 -1) (-1 1 -1) (-1 -1 1) (1 -1 1) (1 1 1) (-1 1 1));
blocks (hex (0 1 2 3 4 5 6 7) (8 8 8) simpleGrading (1 1 1));
boundary (box {type wall; faces ((0 4 7 3) (1 2 6 5) (0 1 5 4) (3 7 6 2) (0 3 2 1) (4 5 6 7));});
)";
inline constexpr const char* kBallSnappyDict = R"(
castellatedMesh true; snap true; addLayers false;
geometry { ball { type searchableSphere; centre (0 0 0); radius 0.45; } }
castellatedMeshControls {
  maxLocalCells 100000; maxGlobalCells 1000000; minRefinementCells 0; nCellsBetweenLevels 1;
  features (); refinementSurfaces { ball { level (1 1); patchInfo { type wall; } } }
  resolveFeatureAngle 30; refinementRegions { }
  locationInMesh (0.71 0.73 0.77); allowFreeStandingZoneFaces true; }
snapControls { nSmoothPatch 3; tolerance 2.0; nSolveIter 30; nRelaxIter 5; nFeatureSnapIter 10;
  implicitFeatureSnap false; explicitFeatureSnap false; multiRegionFeatureSnap false; }
addLayersControls { relativeSizes true; layers { } expansionRatio 1.0; finalLayerThickness 0.3; minThickness 0.1;
  nGrow 0; featureAngle 60; nRelaxIter 3; nSmoothSurfaceNormals 1; nSmoothNormals 3; nSmoothThickness 10;
  maxFaceThicknessRatio 0.5; maxThicknessToMedialRatio 0.3; minMedialAxisAngle 90; nBufferCellsNoExtrude 0;
  nLayerIter 50; }
meshQualityControls { #includeEtc "caseDicts/meshQualityDict"
  nSmoothScale 4; errorReduction 0.75; }
mergeTolerance 1e-6;
)";

/// The ball in the box meshed by blockMesh and snappyHexMesh -overwrite in the case `folder`.
inline CommandResult run_ball_in_box(const std::filesystem::path& folder) {
  write_block_mesh_case(folder, kBallInBox);
  write_text(folder / "system" / "snappyHexMeshDict",
             "FoamFile { version 2.0; format ascii; class dictionary; object snappyHexMeshDict; }\n" +
                 std::string(kBallSnappyDict));
  const CommandResult block = run_block_mesh(folder);
  if (block.exit_code != 0) return block;
  return run_command(snappy_hex_mesh_command() + " -overwrite -case " + shell_quote(folder.string()));
}

/// The points of an ASCII points file, parsed here independently of hotmesh's reader.
inline std::vector<geometry::Vec3> ascii_points(const std::filesystem::path& file) {
  std::istringstream in(test::read_text(file));
  const std::regex point(R"(^\(([^ ]+) ([^ ]+) ([^ ]+)\)$)");
  std::vector<geometry::Vec3> points;
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (std::regex_match(line, m, point)) points.push_back({std::stod(m[1]), std::stod(m[2]), std::stod(m[3])});
  }
  return points;
}

}  // namespace hotmesh::test::foam
