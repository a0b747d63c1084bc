#!/usr/bin/env bash
# Installs the optional peers of bench/peers/ (vds_peers_bench) from Debian 12's
# packages: Embree 3 with TBB (ray parity, as trimesh and Open3D do it) and
# CGAL (Side_of_triangle_mesh). Nothing else in vds uses them, so the build,
# the tests and CI do not need them; tools/install-deps.sh leaves them out.
# Re-run CMake afterwards: each peer is compiled in when it is found.
# libigl (vds_distance_bench's third distance peer) is no Debian package: give
# CMake a libigl checkout, -DVDS_LIBIGL_DIR=PATH (the folder holding
# include/igl); it uses Debian's Eigen (libeigen3-dev, which install-deps.sh
# installs for the tests).
set -euo pipefail
exec bash "$(dirname "$0")/../tools/install-deps.sh" --only libembree-dev libtbb-dev libcgal-dev libopenvdb-dev
