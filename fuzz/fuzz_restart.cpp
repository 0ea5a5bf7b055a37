// hotmesh fuzz: restart files (restart.hmr), as a case's `restart:` key makes `hotmesh deform`
// read them: read_restart against the mesh of the run, then the set-up of the next run from
// the state read (the deflection tables the file holds become curves).
#include "fuzz_support.hpp"
#include "hotmesh/core/input_error.hpp"
#include "hotmesh/setup/case_setup.hpp"
#include "hotmesh/io/restart_file.hpp"
#include "ramp2d_run.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const hotmesh::fuzz::Ramp2dRun& run = hotmesh::fuzz::ramp2d_run();
  static const std::filesystem::path file = hotmesh::fuzz::work_folder() / "restart.hmr";
  hotmesh::fuzz::write_bytes(file, hotmesh::fuzz::as_text(data, size));
  hotmesh::io::RestartState state;
  try {
    state = hotmesh::io::read_restart(file, run.loaded.mesh);
  } catch (const hotmesh::InputError& e) {
    hotmesh::fuzz::require_named(e.what(), file.string());
    return 0;
  }
  try {
    hotmesh::setup::set_up_case(run.c, run.loaded.mesh, &state);
  } catch (const hotmesh::InputError&) {
  }
  return 0;
}
