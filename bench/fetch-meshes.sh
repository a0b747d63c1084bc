#!/usr/bin/env bash
# Downloads the six public meshes the benchmarks and docs name into
# bench/meshes/ (or DIR), from Alec Jacobson's collection of common 3D test
# models (github.com/alecjacobson/common-3d-test-models, a fixed commit), and
# checks each against its SHA-256 at that commit, which is also that of the
# copy the documented figures were measured on. Needs curl or wget; not run by the tests (they build their
# meshes in code).
#   bench/fetch-meshes.sh [DIR]
#   bench/fetch-meshes.sh --scans [DIR]     (default DIR bench/scans)
#
# --scans: five real open scans instead, each from a public GitHub repository at
# a pinned commit (bench/scan_grid/ and the open-scan rows of docs/benchmarks.md):
# | file | triangles | boundary / non-manifold edges | origin |
# | scene0470_00.ply | 127,003 | 8,327 / 99 | ScanNet room (Structure sensor, BundleFusion), from skanti/Scan2CAD's sample; ScanNet's terms of use: non-commercial research, no redistribution |
# | lato270.ply | 118,779 | 4,541 / 0 | one range map of a laser scan, VCLab ISTI-CNR, MeshLab's sample/rangemaps |
# | bun000.obj | 79,312 | 1,186 / 0 | the Stanford bunny's raw range scan bun000, triangulated (Stanford 3D Scanning Repository terms) |
# | max-planck-partial.obj | 63,347 | 439 / 0 | part of the Max Planck bust scan (AIM@SHAPE), alecjacobson/geometry-processing-registration |
# | laurana50k.ply | 49,954 | 302 / 0 | the Laurana bust scan, VCLab ISTI-CNR, MeshLab's sample folder |
# They are fetched for your own measurements and are not redistributed by vds.
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
scans=0
if [ "${1:-}" = --scans ]; then scans=1; shift; fi
dir="${1:-bench/meshes}"
base="https://raw.githubusercontent.com/alecjacobson/common-3d-test-models/01f6c7e30ebbef533b76cba95ff74f97317b7e14/data"
declare -A url sha256
if [ "$scans" = 1 ]; then
  dir="${1:-bench/scans}"
  gh=https://raw.githubusercontent.com
  meshlab=$gh/cnr-isti-vclab/meshlab/684885ade5e0075c0156f7120751e6a0fa1cf8a7/sample
  url=(
    [scene0470_00.ply]=$gh/skanti/Scan2CAD/99c8b9565617b43a9ad03d0dbeb9141805b00618/Assets/scannet-sample/scene0470_00/scene0470_00_vh_clean_2.ply
    [lato270.ply]=$meshlab/rangemaps/lato270.ply
    [bun000.obj]=$gh/dengnantianjie/3dcoursework/fdabb8f051a5e2b209fe9e5ac5fe989588413f3c/bunny/data/bun000.obj
    [max-planck-partial.obj]=$gh/alecjacobson/geometry-processing-registration/213c64a753880b31befceb33575cb4e9cd6b0997/data/max-registration-partial.obj
    [laurana50k.ply]=$meshlab/Laurana50k.ply
  )
  sha256=(
    [scene0470_00.ply]=46d6a1d148f5e1f9099d70d78c844eba32208fadc3a95e7e7f73ce5ca5616c05
    [lato270.ply]=ccc9c9c95883ef0d3be225d0fad4cdcee21442d5d7df7fa52e6b5358fb40a218
    [bun000.obj]=67a5485d98aaea2ad55c18ca22167e74056697f39901c512a747c7c7458bf7a1
    [max-planck-partial.obj]=84654c4f47101c0e1a9d14fc410cea6759502a02bfeeb82cd240c6975cf70364
    [laurana50k.ply]=0809eca64fe06d9df4760a864fe24c38e47334be34efd64292f6d6afe3a66b4a
  )
  names=(scene0470_00.ply lato270.ply bun000.obj max-planck-partial.obj laurana50k.ply)
else
  names=(spot.obj fandisk.obj rocker-arm.obj stanford-bunny.obj teapot.obj suzanne.obj)
  for name in "${names[@]}"; do url[$name]="$base/$name"; done
fi
sha256+=(
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
for name in "${names[@]}"; do
  target="$dir/$name"
  if [ ! -s "$target" ]; then
    get "${url[$name]}" "$target.part" || { rm -f "$target.part"; echo "fetch-meshes: could not download ${url[$name]}" >&2; exit 1; }
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
