#!/usr/bin/env bash
# Re-measures every VM figure of the README's table "Benchmarks and accuracy" that a program
# of bench/ prints, in one command, about 9 minutes on 2 cores (at load 2-3), and prints
# each as one line with the commit and the machine, then the full tables they come from:
#   classification (CPU, GL compute), bakes, .vds file size, accuracy at 2048   vds_bench
#   certified and exact answers; occupancy sweeps against per-point answers     vds_query_bench
#   the exact occupancy grid of spot at 256^3, the whole command               vds voxelize
#   random points and a 512^3 grid against Embree's ray parity                 vds_peers_bench (built with Embree)
#   exact distances against CGAL and Embree; SDF grids at 256^3                vds_distance_bench
#   open meshes by the generalized winding number; their grids at 256^3        vds_gwn_bench, vds voxelize
#   validation and the auto axis's count of a 1M-triangle mesh                 vds_axis_bench
#   the exact classifier against the brute-force loop                         vds_exact_bench
#   real open scans' GWN grids, SDF bands, sprite against exact (where      vds_scan_grid_bench,
#   bench/fetch-meshes.sh --scans fetched them into bench/scans; VDS_SCANS=DIR) vds_gwn_bench
# The H200 rows and certified-gpu (bench/gpu_round.sh, vds_certified_bench) are measured apart.
#   bench/headline.sh [BUILD_DIR]      (default build; configured with VDS_BUILD_BENCHMARKS=ON)
# Meshes: bench/meshes (bench/fetch-meshes.sh downloads them) or VDS_MESHES=DIR.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
meshes="${VDS_MESHES:-bench/meshes}"
if ! ls "$meshes"/*.obj > /dev/null 2>&1; then
  echo "headline: no .obj meshes in $meshes: run bench/fetch-meshes.sh first (or set VDS_MESHES=DIR)" >&2
  exit 1
fi
if [ ! -f "$build/CMakeCache.txt" ]; then
  echo "headline: $build is not a CMake build folder: cmake -S . -B $build -G Ninja -DCMAKE_BUILD_TYPE=Release" >&2
  exit 1
fi
targets=(vds_bench vds_query_bench vds_peers_bench vds_distance_bench vds_gwn_bench vds_axis_bench vds_exact_bench
         vds_scan_grid_bench vds_tool)
cmake --build "$build" --target "${targets[@]}" > /dev/null

commit="$(git rev-parse --short=7 HEAD 2>/dev/null || echo unknown)"
git diff --quiet HEAD -- 2>/dev/null || commit="$commit + uncommitted changes"
cpu="$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)"
machine="$(nproc)-core $(uname -m) ($cpu), $(free -g | awk '/^Mem:/ {print $2}') GiB, load $(cut -d' ' -f1-3 /proc/loadavg)"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
bin="$build/bench"
vds="$build/tools/vds"

since() { awk -v start="$1" -v end="$(date +%s.%N)" 'BEGIN { printf "%.3f", end - start }'; }
# step NAME COMMAND...: COMMAND's output into $out/NAME.txt, its seconds said on stderr.
step() {
  local name="$1" start
  shift
  start=$(date +%s.%N)
  "$@" > "$out/$name.txt"
  echo "headline: $name: $(since "$start") s, load $(cut -d' ' -f1 /proc/loadavg)" >&2
}
# voxelize NAME MESH ARGS...: the whole `vds voxelize` command's wall seconds, best of 3, into $out/NAME.seconds.
voxelize() {
  local name="$1" mesh="$2" start
  shift 2
  for run in 1 2 3; do
    start=$(date +%s.%N)
    "$vds" voxelize "$mesh" -o "$out/grid.npy" --quiet "$@" > /dev/null
    echo "$(basename "$mesh" .obj) $(since "$start")" >> "$out/$name.seconds"
  done
}

step bench "$bin/vds_bench" --meshes "$meshes" --resolutions 1024 --points 10000000 --classify-resolution 2048
step query "$bin/vds_query_bench" --points 2000000 --grids 256 --resolution 1024 --threads 2 \
  "$meshes/spot.obj" "$meshes/fandisk.obj" "$meshes/rocker-arm.obj"
voxelize voxelize-spot "$meshes/spot.obj" --dims 256
step peers "$bin/peers/vds_peers_bench" --points 1000000 --grids 512 --no-generated --cgal-limit 1000000 \
  --threads 2 --mesh-dir "$meshes"
step distance-generated "$bin/vds_distance_bench" --sdf 0 --rounds 2
step distance-meshes "$bin/vds_distance_bench" --sdf 0 --rounds 2 "$meshes"/*.obj
step sdf-grids "$bin/vds_distance_bench" --points 1000 --rounds 1 --brute 10 --sdf 256 --full-grid
step gwn "$bin/vds_gwn_bench" --points 200000 --resolution 1024 --dims 64 --threads 1 \
  "$meshes/stanford-bunny.obj" "$meshes/teapot.obj" "$meshes/suzanne.obj"
for mesh in stanford-bunny teapot suzanne; do
  voxelize voxelize-gwn "$meshes/$mesh.obj" --dims 256 --rule generalized-winding --threads 2
done
step axis "$bin/vds_axis_bench" --runs 5 --sphere --no-bake
step exact "$bin/vds_exact_bench" "$meshes/fandisk.obj" "$meshes/rocker-arm.obj" "$meshes/spot.obj"
scans=()
for f in "${VDS_SCANS:-bench/scans}"/*.ply "${VDS_SCANS:-bench/scans}"/*.obj; do [ -f "$f" ] && scans+=("$f"); done
if [ ${#scans[@]} -gt 0 ]; then
  step scans "$bin/vds_scan_grid_bench" --threads 2 "${scans[@]}"
  step scans-gwn "$bin/vds_gwn_bench" --points 200000 --resolution 1024 --dims 64 --threads 1 --no-generated "${scans[@]}"
else
  echo "headline: no scans in ${VDS_SCANS:-bench/scans} (bench/fetch-meshes.sh --scans): their row is left out" >&2
  : > "$out/scans.txt"
  : > "$out/scans-gwn.txt"
fi

python3 bench/headline.py "$out" "$commit" "$machine, at the end $(cut -d' ' -f1-3 /proc/loadavg)"
for name in bench query peers distance-generated distance-meshes sdf-grids gwn axis exact scans scans-gwn; do
  echo
  cat "$out/$name.txt"
done
