#!/usr/bin/env bash
# hotmesh: install the Debian packages hotmesh builds, tests and runs with, and the npm
# package of the browser test (playwright-core, into tests/browser/node_modules).
# Idempotent: installs only what is missing. Works as root or through sudo.
#   scripts/install-deps.sh            build + test dependencies
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config git ccache
  # geometry kernel
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev
  libocct-data-exchange-dev libtbb-dev
  # numerics
  libeigen3-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  # the amg linear solver: PETSc 3.18 (with hypre) on Open MPI; mpirun for parallel runs
  petsc-dev openmpi-bin
  # case files, command line, logging
  libyaml-cpp-dev libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev
  # hotmesh serve: HTTP server
  libcpp-httplib-dev
  # pictures (PNG and SVG)
  libcairo2-dev
  # engine CFD meshes: CGNS (HDF5 and ADF files) and gzipped OpenFOAM polyMesh files
  libcgns-dev zlib1g-dev
  # the Python module (python/: pybind11, for Debian's Python 3) and its pytest tests
  pybind11-dev python3-dev python3-pytest
  # tests: GoogleTest, plus real external tools that check our files
  # (gmsh writes every .msh flavour we read; VTK's XML reader is the one ParaView uses)
  libgtest-dev libgmock-dev gmsh python3 python3-vtk9 python3-numpy
  # (gmsh's own tutorials, whose meshes the gmsh reader is tested on)
  gmsh-doc
  # (cgnscheck checks the CGNS files hotmesh writes; OpenFOAM's blockMesh makes polyMesh
  # folders and its checkMesh checks the ones hotmesh moves)
  cgns-convert openfoam
  # (the polyMesh folders of OpenFOAM's tutorials are seeds of the foam fuzz target)
  openfoam-examples
  # (the CalculiX tests run the real ccx: it writes the .frd/.dat files hotmesh reads, and
  # the coupled_disc sample solves its disc with it; CalculiX's own test decks and results
  # are seeds of the fuzz targets)
  calculix-ccx calculix-ccx-test
  # the browser test of hotmesh serve's page: Debian's Chromium, driven by playwright-core
  chromium
  # the fuzz targets (scripts/fuzz.sh): clang 14 with libFuzzer and the sanitizers'
  # runtimes (libclang-rt), and its OpenMP runtime
  clang libclang-rt-14-dev libomp-14-dev
)
# Node.js and npm for the browser test, unless a node is there already (a NodeSource node
# ships its own npm and conflicts with Debian's npm package).
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  packages+=(nodejs npm)
fi

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done

if ((${#missing[@]} == 0)); then
  echo "hotmesh: all ${#packages[@]} Debian packages present"
else
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
fi

# playwright-core at the version package-lock.json pins (never `playwright install`: the
# browser is Debian's). Run as the user who called sudo, so node_modules stays theirs.
browser=tests/browser
wanted=$(node -p "require('./$browser/package-lock.json').packages['node_modules/playwright-core'].version")
have=$(node -p "try { require('./$browser/node_modules/playwright-core/package.json').version } catch { '' }")
if [[ "$have" == "$wanted" ]]; then
  echo "hotmesh: playwright-core $have present"
else
  echo "hotmesh: installing playwright-core $wanted into $browser/node_modules"
  as_user=()
  if ((EUID == 0)) && [[ -n "${SUDO_USER:-}" ]]; then as_user=(sudo -u "$SUDO_USER"); fi
  (cd "$browser" && "${as_user[@]}" npm ci --no-audit --no-fund --loglevel=error)
fi
