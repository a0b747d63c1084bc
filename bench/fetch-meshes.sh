#!/usr/bin/env bash
# Downloads the six public meshes the benchmarks and docs name into
# bench/meshes/ (or DIR), from Alec Jacobson's collection of common 3D test
# models (github.com/alecjacobson/common-3d-test-models, a fixed commit), and
# checks each against its SHA-256 at that commit, which is also that of the
# copy the documented figures were measured on. Needs curl or wget; not run by the tests (they build their
# meshes in code).
#   bench/fetch-meshes.sh [DIR]
#
# | file | triangles | closed | origin |
# | spot.obj | 5,856 | yes | Keenan Crane's cow (his model repository, CC0) |
# | fandisk.obj | 12,946 | yes | CAD part (Pratt & Whitney / Hugues Hoppe) |
# | rocker-arm.obj | 20,088 | yes | INRIA rocker arm (genus > 0) |
# | stanford-bunny.obj | 69,451 | no: holes in the base | Stanford 3D Scanning Repository |
# | teapot.obj | 6,320 | no: lid and spout not joined | Martin Newell's Utah teapot |
# | suzanne.obj | 968 | no: separate eyes | Blender's Suzanne |
set -euo pipefail
cd "$(dirname "$0")/.."
dir="${1:-bench/meshes}"
base="https://raw.githubusercontent.com/alecjacobson/common-3d-test-models/01f6c7e30ebbef533b76cba95ff74f97317b7e14/data"
declare -A sha256=(
  [spot.obj]=0738b5e8608fed74e5e8c7aa8dd0af97b4b74f9f6cbf7aac84cd7e40b2e44a75
  [fandisk.obj]=ea5bab2fbf545b1915f0d9faf6cc61ff8c18e0d8174ad61f8e35de15d8f6e3f8
  [rocker-arm.obj]=590257e6d01e689354821d807854306c3bfbb02d9cca73404d5a4924f105c287
  [stanford-bunny.obj]=1eb35d1e21ce99e5ce911353b6be278990713448dd9e8f5c9387f9de39b32205
  [teapot.obj]=1b5396fedd74b577e32cef41146582c2f2e1a050d5b4915193c0ac1ad4187ed4
  [suzanne.obj]=d8684326f9bd8cfc24d3d302c1042fa16f63d2e66e49ed56b413fa20bed271e6
)
if command -v curl > /dev/null; then
  get() { curl -fsSL --retry 3 -o "$2" "$1"; }
elif command -v wget > /dev/null; then
  get() { wget -q -O "$2" "$1"; }
else
  echo "fetch-meshes: needs curl or wget (apt-get install curl)" >&2
  exit 1
fi
mkdir -p "$dir"
bad=0
for name in spot.obj fandisk.obj rocker-arm.obj stanford-bunny.obj teapot.obj suzanne.obj; do
  target="$dir/$name"
  if [ ! -s "$target" ]; then
    get "$base/$name" "$target.part" || { rm -f "$target.part"; echo "fetch-meshes: could not download $base/$name" >&2; exit 1; }
    mv "$target.part" "$target"
  fi
  if [ "$(sha256sum < "$target" | cut -d' ' -f1)" = "${sha256[$name]}" ]; then
    echo "fetch-meshes: $target"
  else
    echo "fetch-meshes: $target differs from the file at the pinned commit (SHA-256): delete it and run again" >&2
    bad=1
  fi
done
exit "$bad"
