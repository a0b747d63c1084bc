#!/usr/bin/env bash
# Installs the build tree into a temporary prefix, builds tests/install_gl as
# an outside renderer with its own EGL context, and runs it.
#   renderer_test.sh BUILD_DIR SOURCE_DIR [CXX_FLAGS [PRELOAD]]
# CXX_FLAGS: the sanitizer flags of a sanitized build (the renderer links its
# instrumented libraries); PRELOAD: what the renderer alone runs with.
set -euo pipefail
build=$1 source=$2 flags=${3:-} preload=${4:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >/dev/null
cmake -S "$source/tests/install_gl" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/build" >/dev/null
if [ -n "$preload" ]; then LD_PRELOAD="$preload" "$work/build/renderer"; else "$work/build/renderer"; fi
