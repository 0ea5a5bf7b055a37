// hotmesh fuzz: the ramp2d run of the state-file targets (see ramp2d_run.hpp).
#include "ramp2d_run.hpp"

#include "fuzz_support.hpp"

namespace hotmesh::fuzz {

const Ramp2dRun& ramp2d_run() {
  static const Ramp2dRun run = [] {
    io::Case c = io::read_case(source_file("samples/ramp2d/ramp2d-sliding.yaml"));
    io::LoadedMesh loaded = io::read_mesh(c.mesh);
    auto inputs = io::input_fingerprints(c);
    return Ramp2dRun{std::move(c), std::move(loaded), std::move(inputs)};
  }();
  return run;
}

}  // namespace hotmesh::fuzz
