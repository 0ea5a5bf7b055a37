// hotmesh fuzz: checkpoint files (checkpoint.hmc), as `hotmesh deform --resume` reads them:
// first the header alone (read_checkpoint_info), then the whole file checked against the
// run's mesh and input files (read_checkpoint).
#include "fuzz_support.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/io/checkpoint_file.hpp"
#include "ramp2d_run.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const hotmesh::fuzz::Ramp2dRun& run = hotmesh::fuzz::ramp2d_run();
  static const std::filesystem::path file = hotmesh::fuzz::work_folder() / "checkpoint.hmc";
  hotmesh::fuzz::write_bytes(file, hotmesh::fuzz::as_text(data, size));
  try {
    hotmesh::io::read_checkpoint_info(file);
  } catch (const hotmesh::InputError& e) {
    hotmesh::fuzz::require_named(e.what(), file.string());
  }
  try {
    hotmesh::io::read_checkpoint(file, run.loaded.mesh, run.inputs);
  } catch (const hotmesh::InputError& e) {
    hotmesh::fuzz::require_named(e.what(), file.string());
  }
  return 0;
}
