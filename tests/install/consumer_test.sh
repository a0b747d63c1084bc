#!/usr/bin/env bash
# Installs the build tree into a temporary prefix, builds tests/install as an
# outside project that links vds::core alone, runs it, and checks that the
# program loads no GL or EGL library.
#   consumer_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 source=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >/dev/null
cmake -S "$source/tests/install" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/build" >/dev/null
"$work/build/consumer"
if ldd "$work/build/consumer" | grep -E 'libEGL|libGL|libOpenGL'; then
  echo "consumer_test: a program linking vds::core alone loads GL" >&2
  exit 1
fi
echo "consumer_test: no GL library in the consumer"
