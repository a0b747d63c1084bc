#!/usr/bin/env bash
# Re-measures the README's headline figures (the first three rows of its table
# "Benchmarks and accuracy": CPU and GL-compute classification of 10M random
# points against sprites at 2048, and the bake at 1024 by fragment lists, the
# CPU baker and depth peeling) in one command, about 3 minutes on 2 cores, and
# prints them with the commit and the machine they were measured on, then the
# full tables they come from.
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
cmake --build "$build" --target vds_bench > /dev/null

commit="$(git rev-parse --short=7 HEAD 2>/dev/null || echo unknown)"
git diff --quiet HEAD -- 2>/dev/null || commit="$commit + uncommitted changes"
cpu="$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)"
machine="$(nproc)-core $(uname -m) ($cpu), $(free -g | awk '/^Mem:/ {print $2}') GiB, load $(cut -d' ' -f1-3 /proc/loadavg)"
out="$(mktemp)"
trap 'rm -f "$out"' EXIT
"$build/bench/vds_bench" --meshes "$meshes" --resolutions 1024 --points 10000000 --classify-resolution 2048 > "$out"

python3 - "$out" "$commit" "$machine" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
renderer = re.search(r"GL[^\n]*(llvmpipe|NVIDIA|AMD|Intel|Mesa)[^\n]*", text)

def tables():
    """Every markdown table of the output: (header cells, rows of cells)."""
    for block in re.split(r"\n\s*\n", text):
        lines = [l for l in block.splitlines() if l.startswith("|")]
        if len(lines) > 2:
            cells = [[c.strip() for c in l.strip("|").split("|")] for l in lines]
            yield cells[0], cells[2:]

def column(header, rows, name, keep=lambda row: True):
    i = header.index(name)
    return [float(r[i].rstrip("x")) for r in rows if keep(r) and re.match(r"^[0-9.]+x?$", r[i])]

def span(values, scale=1.0, unit=""):
    return "%.3g–%.3g%s" % (min(values) * scale, max(values) * scale, unit) if values else "-"

print("vds headline figures, commit %s" % sys.argv[2])
print("machine: %s" % sys.argv[3])
if renderer:
    print(renderer.group(0).strip())
for header, rows in tables():
    if "CPU 1 thr" in header:
        one, two, exact = (column(header, rows, n) for n in ("CPU 1 thr", "CPU 2 thr", "exact"))
        gpu = column(header, rows, "GPU host -> host") + column(header, rows, "GPU resident random") \
            + column(header, rows, "GPU resident coherent")
        ratio = [t / e for t, e in zip(two, exact) if e > 0]
        same = all(r[header.index("GPU == CPU")] == "yes" for r in rows)
        print("classification, 10M random points, sprites at 2048, CPU: %s M points/s on 2 threads, %s on 1; "
              "%s the exact classifier" % (span(two, 1e3), span(one, 1e3), span(ratio, unit="x")))
        print("classification on GL compute, host arrays or resident GL buffers: %s M points/s, "
              "answers identical to the CPU's: %s" % (span(gpu, 1e3), "yes" if same else "NO"))
    if "cpu / lists" in header:
        bundled = lambda r: r[0].endswith(".obj")
        same = all(r[header.index("lists == peel")] == "yes" for r in rows)
        print("bake at 1024 on the six public meshes: lists %s the CPU baker's speed (%s in CPU time), "
              "%s faster than peeling; layers bit-identical to peeling's: %s"
              % (span(column(header, rows, "cpu / lists", bundled), unit="x"),
                 span(column(header, rows, "(CPU time)", bundled), unit="x"),
                 span(column(header, rows, "peel / lists", bundled), unit="x"), "yes" if same else "NO"))
print()
PY
cat "$out"
