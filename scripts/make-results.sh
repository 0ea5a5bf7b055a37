#!/usr/bin/env bash
# hotmesh: builds Release and regenerates the samples' results pages (docs/results/*.md and
# docs/results/img/) from fresh runs. Numbers depend on the machine and its load.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DHOTMESH_WERROR=ON
cmake --build build -j "$(nproc)"
/usr/bin/python3 scripts/make-results.py build
