// hotmesh fuzz: CAD files through OpenCASCADE, as `hotmesh cad`, `curve`, `check`, `deform`
// and the service read them (CadModel::read: the transfer, then every face's kind, bounds and
// axis). Built twice: fuzz_step writes the input to a .step file, fuzz_iges to an .igs file.
#include "fuzz_support.hpp"
#include "hotmesh/geometry/cad_model.hpp"
#include "hotmesh/core/input_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path file = hotmesh::fuzz::work_folder() / ("fuzz" HOTMESH_FUZZ_CAD_EXTENSION);
  hotmesh::fuzz::write_bytes(file, hotmesh::fuzz::as_text(data, size));
  const hotmesh::fuzz::OcctLeaksIgnored occt_leaks;
  try {
    hotmesh::geometry::CadModel::read(file);
  } catch (const hotmesh::InputError& e) {
    hotmesh::fuzz::require_named(e.what(), file.string());
  }
  return 0;
}
