#!/usr/bin/env bash
# The test suite built Debug (asserts on) with AddressSanitizer,
# UndefinedBehaviorSanitizer and -Werror, into build-sanitize/: any memory
# error, leak or undefined behaviour fails the test that caused it, and any
# warning fails the build. GL tests included (llvmpipe without a GPU).
# Left out here, and run by tests/run_tests.sh instead: the Python module
# (an uninstrumented interpreter cannot load an ASan library), the
# option-combination test (label "build"; it builds with its own flags) and
# the benchmark programs (built and run there; under the sanitizers they
# only cost CI minutes, OpenVDB's meshToLevelSet peer most).
# Expects tools/install-deps.sh to have run; ccache is used where installed.
set -euo pipefail
cd "$(dirname "$0")/.."
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
# No leak suppressions: GL tests keep the driver loaded (tests/CMakeLists.txt),
# and nothing then leaks. Set before the build, which runs
# each test program to list its tests.
export ASAN_OPTIONS="detect_leaks=1:check_initialization_order=1:strict_init_order=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# -O1 with the Debug flags (asserts stay on): at -O0 every glm vector
# operation is an instrumented out-of-line call, which made the exact and
# winding-number suites 7 to 12 times slower than at -O1 (400 s for one test).
cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g -O1" \
      -DVDS_BUILD_TESTS=ON -DVDS_SANITIZE=ON -DVDS_WERROR=ON -DVDS_PYTHON=OFF -DVDS_BUILD_BENCHMARKS=OFF \
      "${launcher[@]}"
cmake --build build-sanitize -j "$(nproc)"
export VDS_REQUIRE_GL="${VDS_REQUIRE_GL:-1}"
ctest --test-dir build-sanitize --output-on-failure -j "$(nproc)" --timeout 600 -LE rebuild
