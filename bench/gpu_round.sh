#!/usr/bin/env bash
# One round of the GPU figures of docs/benchmarks.md ("The GPU on an NVIDIA H200",
# "Exact answers on the GPU"),
# for a machine lent a GPU for minutes: every table in one call, each with its
# plain kernels of the same run, and the GPU's clocks logged beside them
# (nvidia-smi, where there is one: a GL figure at half a CUDA one's rate with
# the SM clock at half says the clock, not the program).
#   bench/gpu_round.sh BUILD_DIR MESH_DIR [OUT_DIR]     (about 4 minutes on an H200)
# BUILD_DIR: a Release build with VDS_BUILD_BENCHMARKS=ON; MESH_DIR: .obj meshes
# (bench/fetch-meshes.sh fills bench/meshes), the generated knot and sphere
# added; OUT_DIR (default: out/gpu-round) gets one markdown file a table and
# clocks.csv. VDS_ROUND_SMOKE=1: tiny sizes, to check the round runs (llvmpipe).
set -uo pipefail
if [ $# -lt 2 ]; then
  echo "usage: bench/gpu_round.sh BUILD_DIR MESH_DIR [OUT_DIR]" >&2
  exit 2
fi
build="$1" meshes="$2" out="${3:-out/gpu-round}"
bench="$build/bench/vds_bench"
[ -x "$bench" ] || { echo "gpu_round: no $bench: build with -DVDS_BUILD_BENCHMARKS=ON" >&2; exit 1; }
mapfile -t files < <(ls "$meshes"/*.obj 2>/dev/null)
[ ${#files[@]} -gt 0 ] || { echo "gpu_round: no .obj meshes in $meshes" >&2; exit 1; }
mkdir -p "$out"
clocks=""
if command -v nvidia-smi > /dev/null; then
  nvidia-smi --query-gpu=timestamp,clocks.sm,clocks.mem,clocks.max.sm,power.draw --format=csv -lms 200 \
    > "$out/clocks.csv" 2>&1 &
  clocks=$!
fi
points=100000000 res=2048 gwn=(--gwn-points 20000000 --gwn-dims 1024) bake=(--resolutions 2048) sizes=(--full)
if [ "${VDS_ROUND_SMOKE:-0}" = 1 ]; then
  points=200000 res=256 gwn=(--gwn-points 20000 --gwn-dims 32) bake=(--resolutions 128) sizes=(--quick --warm-up 0.1)
fi
run() { # NAME SECONDS ARGS...: one table into NAME.md, its status on stdout
  local name="$1" limit="$2"
  shift 2
  timeout "$limit" "$bench" "$@" > "$out/$name.md" 2>&1
  echo "gpu_round: $name: rc $? ($out/$name.md)"
}
# Random parity: the plain kernel's forms (what holds GL below CUDA).
run plain-forms 120 --plain-forms --points "$points" --classify-resolution "$res" --runs 3 "${files[@]}"
# Resident and host-to-host classification, the generalized winding number and its occupancy.
run classify 240 "${sizes[@]}" --classify-only --points "$points" --classify-resolution "$res" "${gwn[@]}" --runs 3 \
  --meshes "$meshes"
# Bakes to the GPU: wall against GPU time (the axis count beside validation).
run bake 180 "${sizes[@]}" --bake-only "${bake[@]}" --no-peel --no-cpu-bake --runs 2 --meshes "$meshes"
# Exact answers on the GPU: certified-gpu against sprite-gpu and CPU certified, every mesh at 1024.
certified="$build/bench/vds_certified_bench" cpoints=20000000
[ "${VDS_ROUND_SMOKE:-0}" = 1 ] && cpoints=200000
if [ -x "$certified" ]; then
  timeout 180 "$certified" --points "$cpoints" --resolution 1024 --runs 3 "${files[@]}" > "$out/certified.md" 2>&1
  echo "gpu_round: certified: rc $? ($out/certified.md)"
fi
[ -n "$clocks" ] && kill "$clocks" 2> /dev/null
exit 0
