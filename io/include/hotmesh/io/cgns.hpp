// hotmesh io: CGNS files (docs/cgns.md). Read: the first base, its unstructured zones (TRI_3
// and QUAD_4 cells in 2D, TETRA_4, PYRA_5, PENTA_6 and HEXA_8 in 3D, typed or MIXED sections;
// BAR_2 / TRI_3 and QUAD_4 boundary sections) and structured zones (i x j quads,
// i x j x k hexes), joined into one conforming mesh through
// their connectivity (or coincident boundary nodes); patches from ZoneBC. Written back: a
// copy of the input with only the grid coordinates replaced. Written new (convert): one
// unstructured zone with a section and a BC per patch.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "hotmesh/io/mesh_files.hpp"
#include "hotmesh/mesh/mesh.hpp"

namespace hotmesh::io {

/// The mesh of a CGNS file (not yet validated) and how to write it back.
struct CgnsMesh {
  mesh::Mesh mesh;
  std::shared_ptr<const MeshWriteBack> write_back;
};

/// How a CGNS file is read.
struct CgnsReadOptions {
  /// Read the file in a child process first, so that a fault of the CGNS or HDF5 library on
  /// a damaged file (a segmentation fault, an abort inside HDF5) is an InputError naming the
  /// file rather than the end of this process. Off only where a fault must surface: the
  /// fuzz target, which looks for them.
  bool check_in_child = true;
};

/// Reads the first base of a CGNS file. Throws hotmesh::InputError naming the file, and the
/// zone, section or BC, for anything hotmesh cannot move.
CgnsMesh read_cgns(const std::filesystem::path& path, const CgnsReadOptions& options = {});

/// Writes `mesh` with its nodes at `points` as a new CGNS (HDF5) file, atomically: one
/// base, one unstructured zone, a cell section, and per patch a face section and a BC
/// (FaceCenter / EdgeCenter point range over that section) named as the patch. A section
/// holding one element type is typed (HEXA_8, TRI_3, ...), one holding several is MIXED.
void write_cgns(const std::filesystem::path& path, const mesh::Mesh& mesh, std::span<const geometry::Vec3> points);

/// What a CGNS file holds, for `hotmesh info`.
struct CgnsSummary {
  struct Section {
    std::string name, type;
    std::int64_t first = 0, last = 0;  ///< element range
  };
  struct Bc {
    std::string name, type, location, point_set, family;
    std::int64_t points = 0;  ///< entries of its point set (2 for a range)
  };
  struct Connection {
    std::string name, kind, donor;  ///< kind: "1to1" or the GridConnectivity type
  };
  struct Zone {
    std::string name, type;          ///< type: "Structured" or "Unstructured"
    std::vector<std::int64_t> size;  ///< as cg_zone_read gives it
    std::vector<Section> sections;
    std::vector<Bc> bcs;
    std::vector<Connection> connections;
    int solutions = 0;  ///< FlowSolution_t nodes
  };
  struct Base {
    std::string name;
    int cell_dimension = 0, physical_dimension = 0;
    std::vector<Zone> zones;
    std::vector<std::string> families;
  };
  std::string file_type;  ///< "HDF5" or "ADF"
  std::vector<Base> bases;
};
CgnsSummary describe_cgns(const std::filesystem::path& path, const CgnsReadOptions& options = {});

}  // namespace hotmesh::io
