// hotmesh fuzz: writes the small CGNS files of the tests (tests/support/cgns_files.hpp) into a
// folder, as seeds of fuzz_cgns (scripts/fuzz.sh): unstructured 2D and 3D with MIXED sections
// and BCs by element ranges, lists and vertices; structured 2D and 3D in two zones, 1-to-1,
// periodic and abutting connections, families. Usage: cgns_seeds FOLDER
#include <cstdio>
#include <exception>
#include <filesystem>

#include "cgns_files.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: cgns_seeds FOLDER\n");
    return 2;
  }
  const std::filesystem::path folder = argv[1];
  try {
    std::filesystem::create_directories(folder);
    hotmesh::test::write_unstructured_2d(folder / "unstructured_2d_mixed.cgns");
    hotmesh::test::write_unstructured_3d(folder / "unstructured_3d_mixed.cgns");
    hotmesh::test::write_structured_2d(folder / "structured_2d_one_to_one.cgns");
    hotmesh::test::write_structured_3d(folder / "structured_3d_coincident.cgns");
    hotmesh::test::write_structured_periodic_2d(folder / "structured_2d_periodic.cgns");
    hotmesh::test::write_unstructured_two_zones(folder / "unstructured_2d_abutting.cgns", true);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cgns_seeds: %s\n", e.what());
    return 1;
  }
  return 0;
}
