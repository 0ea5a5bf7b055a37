#!/usr/bin/env bash
# hotmesh: install the Debian packages hotmesh builds, tests and runs with.
# Idempotent: installs only what is missing. Works as root or through sudo.
#   scripts/install-deps.sh            build + test dependencies
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config git
  # geometry kernel
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev
  libocct-data-exchange-dev libtbb-dev
  # numerics
  libeigen3-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  # case files, command line, logging
  libyaml-cpp-dev libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev
  # pictures (PNG and SVG)
  libcairo2-dev
  # tests: GoogleTest, plus real external tools that check our files
  # (gmsh writes every .msh flavour we read; VTK's XML reader is the one ParaView uses)
  libgtest-dev libgmock-dev gmsh python3 python3-vtk9 python3-numpy
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  echo "hotmesh: all ${#packages[@]} Debian packages present"
  exit 0
fi

if ((EUID == 0)); then
  as_root=()
elif command -v sudo >/dev/null 2>&1; then
  as_root=(sudo)
else
  echo "hotmesh: missing packages (${missing[*]}) and neither root nor sudo available" >&2
  exit 1
fi

echo "hotmesh: installing ${#missing[@]} Debian packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${as_root[@]}" apt-get update -qq
"${as_root[@]}" env DEBIAN_FRONTEND=noninteractive \
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
