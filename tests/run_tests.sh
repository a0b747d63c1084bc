#!/usr/bin/env bash
# The whole test suite from a fresh Debian 12 machine: installs the packages,
# builds (Release, tests on) into build-tests/, runs every test with ctest in
# parallel but those that rebuild the project (label "rebuild": the option
# matrix, the GL-off build, the outside-project installs), then those one at
# a time with limits that fit a loaded 2-core machine
# (tests/run_rebuild_tests.sh; VDS_SKIP_REBUILD=1 leaves them out).
# GL tests run on a real headless context (llvmpipe without a GPU); a missing
# GL fails them rather than skipping (set VDS_REQUIRE_GL=0 to allow skips).
# ccache is used where it is installed.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install-deps.sh
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S . -B build-tests -G Ninja -DCMAKE_BUILD_TYPE=Release -DVDS_BUILD_TESTS=ON "${launcher[@]}"
cmake --build build-tests -j "$(nproc)"
export VDS_REQUIRE_GL="${VDS_REQUIRE_GL:-1}"
ctest --test-dir build-tests --output-on-failure -j "$(nproc)" --timeout 600 -LE rebuild
if [ "${VDS_SKIP_REBUILD:-0}" != 1 ]; then bash tests/run_rebuild_tests.sh; fi
