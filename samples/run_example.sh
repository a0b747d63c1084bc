#!/usr/bin/env bash
# The main job end to end on the bundled example, from a fresh Debian 12
# machine: install, build, bake Spot the cow into a sprite, classify a grid of
# points with the sprite and with the exact classifier, and render Spot
# clipped by a second sprite to a PNG. Outputs go to out/example/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DVDS_BUILD_TESTS=OFF -DVDS_BUILD_BENCHMARKS=OFF
cmake --build build -j "$(nproc)"
vds=build/tools/vds
out=out/example
mkdir -p "$out"

echo "== bake"
$vds bake samples/data/spot.obj -o "$out/spot.vds" --resolution 1024
$vds info "$out/spot.vds"

echo "== classify"
# A 64^3 grid of points over Spot's box (mesh coordinates).
awk 'BEGIN { n = 64; for (i = 0; i < n; i++) for (j = 0; j < n; j++) for (k = 0; k < n; k++)
  printf "%.6f %.6f %.6f\n", -0.5 + 1.0 * (i + 0.5) / n, -0.75 + 1.75 * (j + 0.5) / n, -0.7 + 1.8 * (k + 0.5) / n }' \
  > "$out/points.txt"
$vds classify "$out/spot.vds" "$out/points.txt" -o "$out/labels.txt"
$vds classify "$out/spot.vds" "$out/points.txt" -o "$out/labels-gpu.txt" --method sprite-gpu
$vds classify --method exact --mesh samples/data/spot.obj "$out/points.txt" -o "$out/labels-exact.txt"
$vds classify --method certified --mesh samples/data/spot.obj "$out/points.txt" -o "$out/labels-certified.txt"
cmp -s "$out/labels.txt" "$out/labels-gpu.txt" && echo "CPU and GPU labels are identical"
cmp -s "$out/labels-exact.txt" "$out/labels-certified.txt" && echo "certified labels equal the exact classifier's"
echo "labels differing from the exact classifier: $(paste "$out/labels.txt" "$out/labels-exact.txt" | awk '$1 != $2' | wc -l) of $(wc -l < "$out/points.txt")"

echo "== voxelize"
# An exact 128-cell occupancy grid of Spot as a numpy boolean array (numpy.load reads it).
$vds voxelize samples/data/spot.obj --dims 128 -o "$out/spot-128.npy" --verbose

echo "== render"
$vds bake samples/data/lens.obj -o "$out/lens.vds" --resolution 512 --quiet
build/samples/vds_clip samples/data/spot.obj --clip "$out/lens.vds" -o "$out/spot-clipped.png" --size 800

echo
echo "outputs in $out/:"
echo "  spot.vds          the sprite (OpenEXR deep image; 'vds info' describes it)"
echo "  points.txt        the points classified"
echo "  labels*.txt       1 inside / 0 outside per point: CPU, GPU, exact, certified"
echo "  spot-128.npy      exact occupancy of 128^3 cells over Spot's box (numpy bool array)"
echo "  spot-clipped.png  Spot clipped pixel-precisely by lens.vds (cut surface red)"
