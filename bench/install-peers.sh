#!/usr/bin/env bash
# Installs the optional peers of bench/peers/ (vds_peers_bench) from Debian 12's
# packages: Embree 3 with TBB (ray parity, as trimesh and Open3D do it) and
# CGAL (Side_of_triangle_mesh). Nothing else in vds uses them, so the build,
# the tests and CI do not need them; tools/install-deps.sh leaves them out.
# Re-run CMake afterwards: each peer is compiled in when it is found.
set -euo pipefail
packages=(libembree-dev libtbb-dev libcgal-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-peers: all packages present"
  exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "install-peers: installing ${missing[*]}"
$sudo apt-get update -q
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
