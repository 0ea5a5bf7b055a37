// hotmesh fuzz: the run whose state files the restart and checkpoint targets read: the
// ramp2d sample with sliding walls (samples/ramp2d/ramp2d-sliding.yaml), whose restart.hmr and
// checkpoint.hmc seed their corpora (scripts/fuzz.sh makes them with the built hotmesh).
#pragma once

#include <vector>

#include "hotmesh/io/case_file.hpp"
#include "hotmesh/io/checkpoint_file.hpp"
#include "hotmesh/io/mesh_files.hpp"

namespace hotmesh::fuzz {

struct Ramp2dRun {
  io::Case c;
  io::LoadedMesh loaded;
  std::vector<io::InputFingerprint> inputs;
};

/// Read once, on first use.
const Ramp2dRun& ramp2d_run();

}  // namespace hotmesh::fuzz
