#!/usr/bin/env bash
# hotmesh: set up on a fresh Debian machine and run the default case.
#   1. installs missing Debian packages (scripts/install-deps.sh; as root or through sudo),
#   2. configures and builds Release in build/ (the command, libhotmesh and the Python module),
#   3. runs hotmesh on the bundled 2D ramp sample (the paper's section 5) and prints where the
#      outputs are.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DHOTMESH_WERROR=ON
cmake --build build -j "$(nproc)"

hotmesh=build/app/hotmesh
out=build/samples-out/ramp2d
echo "== hotmesh deform samples/ramp2d/ramp2d.yaml -o $out"
"$hotmesh" deform samples/ramp2d/ramp2d.yaml -o "$out"
echo
echo "hotmesh is built: $(pwd)/$hotmesh"
echo "outputs of the default case (the paper's 2D ramp) in $(pwd)/$out:"
echo "  deformed.msh, deformed.vtu (open in ParaView), deformed.png and close-ups, report.json"
echo "the Python module: PYTHONPATH=$(pwd)/build/python python3 -c 'import hotmesh' (docs/library.md)"
