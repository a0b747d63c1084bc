#!/usr/bin/env bash
# Installs the build tree into a temporary prefix and builds tests/install
# as an outside project against it:
#   - no internal header (vds/detail, */detail/) is installed, no installed
#     header names a `detail` type or namespace, and a source including every
#     installed header compiles;
#   - a program linking vds::core alone bakes on the CPU, classifies, uses
#     glm's r, g, b names (no GLM define of ours reaches it), and loads no GL
#     or EGL library;
#   - where vds was built with GL, a program embeds a shader of its own with
#     the installed vds_embed_shaders and links vds::gl.
#   consumer_test.sh BUILD_DIR SOURCE_DIR [CXX_FLAGS]
# CXX_FLAGS: what the consumers need to link the installed libraries (the
# sanitizer runtimes of a VDS_SANITIZE build).
set -euo pipefail
build=$1 source=$2 flags=${3:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >"$work/install.log"
include="$work/prefix/include"
internal=$(cd "$include" && find . -path '*detail*' -o -path '*internal*')
if [ -n "$internal" ]; then
  echo "consumer_test: internal headers installed:" $internal >&2
  exit 1
fi
naming=$(cd "$include" && grep -rlE '\bdetail::|namespace detail\b|::detail\b' vds || true)
if [ -n "$naming" ]; then
  echo "consumer_test: installed headers name detail types:" $naming >&2
  exit 1
fi
{
  echo "// Every installed header of vds, included once (the interop adapters but adapted_mesh.h"
  echo "// need the user's Eigen or OpenMesh: tests/interop compiles them where installed)."
  (cd "$include" && find vds -name '*.h' ! -path 'vds/interop/eigen.h' ! -path 'vds/interop/openmesh.h' | sort |
     sed 's|.*|#include <&>|')
} >"$work/every_header.cpp"
echo "consumer_test: $(grep -c '#include' "$work/every_header.cpp") headers installed, none internal"

if ! { cmake -S "$source/tests/install" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
         -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_PREFIX_PATH="$work/prefix" \
         -DVDS_EVERY_HEADER_SOURCE="$work/every_header.cpp" && cmake --build "$work/build"; } >"$work/build.log" 2>&1; then
  cat "$work/build.log" >&2
  echo "consumer_test: the outside project does not build against the installed vds" >&2
  exit 1
fi
"$work/build/consumer"
if ldd "$work/build/consumer" | grep -E 'libEGL|libGL|libOpenGL'; then
  echo "consumer_test: a program linking vds::core alone loads GL" >&2
  exit 1
fi
echo "consumer_test: no GL library in the consumer"
if grep -q 'vds::gl' "$work/prefix"/lib*/cmake/vds/vdsTargets.cmake; then
  "$work/build/gl_consumer"
fi
