#!/usr/bin/env bash
# hotmesh: set up on a fresh Debian machine and run the default case.
#   1. installs missing Debian packages (scripts/install-deps.sh; as root or through sudo),
#   2. configures and builds Release in build/,
#   3. runs hotmesh on the bundled 2D ramp sample and prints where the outputs are.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DHOTMESH_WERROR=ON
cmake --build build -j "$(nproc)"

hotmesh=build/app/hotmesh
out=build/samples-out/ramp2d
mkdir -p "$out"
echo "== hotmesh info samples/ramp2d/ramp2d.msh"
"$hotmesh" info samples/ramp2d/ramp2d.msh
"$hotmesh" convert samples/ramp2d/ramp2d.msh "$out/ramp2d.vtu"
echo
echo "hotmesh is built: $(pwd)/$hotmesh"
echo "outputs of the default case: $(pwd)/$out/ramp2d.vtu (open it in ParaView)"
