#!/usr/bin/env bash
# The tests that rebuild the project or build outside projects against its
# installed package (ctest label "rebuild": every documented option
# combination configures, vds::core builds and passes with GL off, the
# installed package serves outside projects, pip and cmake --install give an
# importable vds). Each is minutes of both cores, so they run one at a time
# with a limit that fits a loaded machine (tests/CMakeLists.txt). Uses the
# build tests/run_tests.sh made (build-tests/), configuring one if missing.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -f build-tests/CTestTestfile.cmake ]; then
  launcher=()
  if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
  cmake -S . -B build-tests -G Ninja -DCMAKE_BUILD_TYPE=Release -DVDS_BUILD_TESTS=ON "${launcher[@]}"
fi
cmake --build build-tests -j "$(nproc)"
export VDS_REQUIRE_GL="${VDS_REQUIRE_GL:-1}"
ctest --test-dir build-tests --output-on-failure -j 1 -L rebuild
