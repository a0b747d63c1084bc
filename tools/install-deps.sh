#!/usr/bin/env bash
# Installs what vds needs to build, test and run on Debian 12, from Debian's
# packages only. Does nothing when everything is already there.
#   tools/install-deps.sh                # what vds needs
#   tools/install-deps.sh --only P ...   # just packages P (bench/install-peers.sh)
set -euo pipefail
packages=(
  cmake ninja-build g++ pkg-config
  libegl-dev libgl-dev libopengl-dev   # OpenGL through EGL (glvnd)
  libgl1-mesa-dri libegl-mesa0         # Mesa's llvmpipe: GL 4.5 core where there is no GPU
  libglm-dev libopenexr-dev libpng-dev libgtest-dev
  libcli11-dev nlohmann-json3-dev     # command lines, JSON reports
  zlib1g-dev                           # the CRC-32 of the tool's .npz grid files (libopenexr-dev brings it too)
  python3-dev pybind11-dev python3-numpy python3-pytest   # the Python module vds and its tests
  python3-pip python3-venv                                # pip install . (pyproject.toml), its test
  python3-dask python3-distributed python3-zarr           # vds.dask: every question on a Dask cluster, grids into Zarr
  libglfw3-dev xvfb xauth              # the interactive viewer (samples/viewer) and its test under Xvfb
  libepoxy-dev                         # tests: vds headers after an application's GL loader
  libcgal-dev                          # tests: the exact predicates against CGAL's exact rationals
  libeigen3-dev libopenmesh-dev        # tests: the header-only Eigen/libigl and OpenMesh adapters
  libopenvdb-dev python3-openvdb       # optional .vdb output (vds::vdb), read back by its tests in C++ and Python
)
if [ "${1:-}" = "--only" ]; then shift; packages=("$@"); fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all packages present"
  exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -q
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
