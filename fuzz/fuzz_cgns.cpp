// hotmesh fuzz: CGNS files through the CGNS library (HDF5 or ADF), as `hotmesh deform`, `info`
// and `convert` read them: read_cgns and the validation read_mesh does; then, for a file read,
// describe_cgns (what `hotmesh info` adds) and its write-back (deformed.cgns: a copy with the
// coordinates replaced, as `hotmesh deform` ends). The input is written to a file in memory (/dev/shm,
// fuzz_support's memory_folder). read_cgns reads it in this process, not in the child process
// the program reads it in first (CgnsReadOptions::check_in_child): a fault of hotmesh or of the
// library is a finding here; the program turns a fault of the library into an InputError
// (tests/io/test_cgns_damage.cpp).
#include "fuzz_support.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/cgns.hpp"
#include "hotmesh/mesh/validate.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path folder = [] {
    const auto path = hotmesh::fuzz::memory_folder() / "cgns";
    std::filesystem::create_directories(path / "out");
    return path;
  }();
  const std::filesystem::path file = folder / "fuzz.cgns";
  hotmesh::fuzz::write_bytes(file, hotmesh::fuzz::as_text(data, size));
  const hotmesh::io::CgnsReadOptions in_process{.check_in_child = false};
  hotmesh::io::CgnsMesh read;
  try {
    read = hotmesh::io::read_cgns(file, in_process);
  } catch (const hotmesh::InputError& e) {
    hotmesh::fuzz::require_named(e.what(), file.string());
    return 0;
  }
  try {
    hotmesh::mesh::validate_mesh(read.mesh);  // its messages are about the mesh; read_mesh adds the file
  } catch (const hotmesh::InputError&) {
    return 0;
  }
  try {
    hotmesh::io::describe_cgns(file, in_process);
  } catch (const hotmesh::InputError& e) {
    hotmesh::fuzz::require_named(e.what(), file.string());
  }
  try {
    read.write_back->write(folder / "out", read.mesh.points, {});
  } catch (const hotmesh::InputError& e) {
    hotmesh::fuzz::require_named(e.what(), folder.string());  // the input, or the copy being written
  }
  return 0;
}
