#!/usr/bin/env bash
# `vds voxelize` holds one slab, never the grid: a 600^3 grid (216 MB of
# labels) is written under an address-space limit of 128 MB, which a program
# holding the grid could not allocate: `vds sdf --propagated`, which does hold
# its grid (864 MB of distances), is refused under the same limit with its one
# line, exit 1. Thread stacks are kept small (glibc sizes them by ulimit -s)
# so that the limit measures the grid, not the machine's core count.
#   slab_memory_test.sh VDS_TOOL
set -euo pipefail
tool=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
# An octahedron: |x| + |y| + |z| <= 1.
cat > "$dir/octahedron.obj" <<'OBJ'
v 1 0 0
v -1 0 0
v 0 1 0
v 0 -1 0
v 0 0 1
v 0 0 -1
f 1 3 5
f 3 2 5
f 2 4 5
f 4 1 5
f 3 1 6
f 2 3 6
f 4 2 6
f 1 4 6
OBJ
limit_kb=$((128 * 1024))
cells=$((600 * 600 * 600))
if (( cells <= limit_kb * 1024 )); then echo "the grid must be larger than the limit"; exit 1; fi
(
  ulimit -s 2048
  ulimit -v "$limit_kb"
  "$tool" voxelize "$dir/octahedron.obj" --dims 600 -o "$dir/grid.npy" --quiet
) > "$dir/out.txt" 2>&1 || { echo "voxelize failed under the limit:"; cat "$dir/out.txt"; exit 1; }
size=$(stat -c %s "$dir/grid.npy")
if (( size != 128 + cells )); then echo "grid.npy has $size bytes, not $((128 + cells))"; exit 1; fi
status=0
(
  ulimit -s 2048
  ulimit -v "$limit_kb"
  "$tool" sdf "$dir/octahedron.obj" --dims 600 --propagated -o "$dir/sdf.npy" --quiet
) > "$dir/sdf.txt" 2>&1 || status=$?
if (( status != 1 )) || ! grep -q "memory" "$dir/sdf.txt" || [[ -e "$dir/sdf.npy" ]]; then
  echo "the limit did not stop a program holding its grid (exit $status):"; cat "$dir/sdf.txt"; exit 1
fi
echo "a 600^3 grid written under a ${limit_kb} KB address-space limit: $(cat "$dir/out.txt")"
