#!/usr/bin/env bash
# The renderer's side end to end, from a fresh Debian 12 machine: install,
# build (as samples/run_example.sh does), then render the samples through
# every representation and the comparison gallery: each scene exactly
# (fragments classified by the exact classifier) and through the VDS,
# slicemaps and solid voxels at equal resolution and equal memory, with
# difference pictures and a table. Outputs go to out/gallery/.
#
#   bash samples/run_gallery.sh               render into out/gallery/
#   bash samples/run_gallery.sh --update-docs also copy the pictures docs/rendering.md shows
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DVDS_BUILD_TESTS=OFF -DVDS_BUILD_BENCHMARKS=OFF
cmake --build build -j "$(nproc)"
out=out/gallery
mkdir -p "$out"

echo "== samples, through each representation"
for with in vds slicemap slicemap-local solid exact; do
  build/samples/vds_clip samples/data/spot.obj --solid samples/data/lens.obj -o "$out/clip-$with.png" --size 384 --with "$with"
  build/samples/vds_styles -o "$out/styles-$with.png" --size 384 --with "$with"
done
build/samples/vds_lens -o "$out/lens-frames" --frames 6 --size 384

echo "== comparison gallery"
build/samples/vds_gallery -o "$out" --size 256 --resolution 64 --scenes clip,clip-intersection,lens,styles

if [[ "${1:-}" == "--update-docs" ]]; then
  docs=docs/images/rendering
  mkdir -p "$docs"
  for scene in clip lens styles; do
    cp "$out/$scene-exact.png" "$out/$scene-vds-res.png" "$out/$scene-vds-res-diff.png" "$docs/"
    for with in slicemap slicemap-local solid; do cp "$out/$scene-$with-mem.png" "$out/$scene-$with-mem-diff.png" "$docs/"; done
  done
  cp "$out/gallery.md" "$docs/gallery.md"
  echo "copied the gallery's pictures and table to $docs/"
fi

echo
echo "outputs in $out/:"
echo "  clip-*.png, styles-*.png    the samples through each lookup (--with)"
echo "  lens-frames/lens-NN.png     the magic lens moved along its path (no re-bake)"
echo "  SCENE-exact.png             the exact reference of each scene"
echo "  SCENE-LOOKUP-res|mem.png    through each lookup at equal resolution / equal memory, and -diff.png"
echo "  gallery.json, gallery.md    differing pixels, memory, frame time (llvmpipe without a GPU)"
