#!/usr/bin/env bash
# Every documented option combination (README, "Build options") configures,
# each into a folder of its own:
#   - tests on with the samples, the tool, the benchmarks or Python off: only
#     tests whose programs exist are registered;
#   - vds added to a parent project with add_subdirectory: it forces no build
#     type, no C++ standard and no GLM define onto the parent, and builds no
#     tests, samples or benchmarks by default;
#   - VDS_BUILD_GL=OFF (vds::core alone) with GL, EGL, PNG, JSON, CLI11 and
#     Python made unfindable: it configures, builds, and its tests pass
#     (the core suite, the .vdb writer's on top of core, and the installed
#     core-only consumer, tests/install).
#   configure_test.sh SOURCE_DIR [GENERATOR]
set -euo pipefail
source=$(cd "$1" && pwd)
generator=${2:-Ninja}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
failures=0

fail() {
  echo "configure_test: $*" >&2
  failures=$((failures + 1))
}

# configure NAME ARGS...: configures into $work/NAME, or reports the log.
configure() {
  local name=$1
  shift
  if ! cmake -S "$source" -B "$work/$name" -G "$generator" -DCMAKE_BUILD_TYPE=Release "$@" \
       >"$work/$name.log" 2>&1; then
    fail "$name: configure failed ($*):"
    tail -n 30 "$work/$name.log" >&2
    return 1
  fi
}

# registered NAME PATTERN: whether a test matching PATTERN is registered in $work/NAME.
registered() {
  ctest --test-dir "$work/$1" -N 2>/dev/null | grep -E "$2" >/dev/null
}

configure samples-off -DVDS_BUILD_TESTS=ON -DVDS_BUILD_SAMPLES=OFF &&
  { ! registered samples-off 'vds_(shadows|refraction)_bad_option' || fail "samples-off: sample tests registered"; }
configure tools-off -DVDS_BUILD_TESTS=ON -DVDS_BUILD_TOOLS=OFF || true
configure benchmarks-off -DVDS_BUILD_TESTS=ON -DVDS_BUILD_BENCHMARKS=OFF || true
configure python-off -DVDS_BUILD_TESTS=ON -DVDS_PYTHON=OFF &&
  { ! registered python-off 'Python\.' || fail "python-off: Python tests registered"; }
configure all-programs-off -DVDS_BUILD_TESTS=ON -DVDS_BUILD_TOOLS=OFF -DVDS_BUILD_SAMPLES=OFF \
  -DVDS_BUILD_BENCHMARKS=OFF -DVDS_PYTHON=OFF || true

# As a subproject: the parent's settings stay the parent's.
mkdir -p "$work/parent"
cat >"$work/parent/CMakeLists.txt" <<CMAKE
cmake_minimum_required(VERSION 3.16)
project(parent LANGUAGES C CXX)
set(CMAKE_CXX_STANDARD 20)
add_subdirectory("$source" vds)
if(NOT "\${CMAKE_BUILD_TYPE}" STREQUAL "")
  message(FATAL_ERROR "vds set the parent's build type to '\${CMAKE_BUILD_TYPE}'")
endif()
if(NOT CMAKE_CXX_STANDARD EQUAL 20)
  message(FATAL_ERROR "vds changed the parent's C++ standard to \${CMAKE_CXX_STANDARD}")
endif()
foreach(option VDS_BUILD_TESTS VDS_BUILD_SAMPLES VDS_BUILD_BENCHMARKS)
  if(\${option})
    message(FATAL_ERROR "\${option} is on by default in a subproject")
  endif()
endforeach()
get_target_property(definitions vds_core INTERFACE_COMPILE_DEFINITIONS)
if(definitions MATCHES "GLM_")
  message(FATAL_ERROR "vds::core gives its consumers GLM defines: \${definitions}")
endif()
CMAKE
if ! cmake -S "$work/parent" -B "$work/parent-build" -G "$generator" >"$work/parent.log" 2>&1; then
  fail "subproject: configure failed:"
  tail -n 30 "$work/parent.log" >&2
fi

# Core alone, with everything the GL layers and the programs need made unfindable.
unfindable=()
for package in OpenGL PNG nlohmann_json CLI11 Python3 pybind11; do
  unfindable+=("-DCMAKE_DISABLE_FIND_PACKAGE_$package=ON")
done
slow='ExactClassifier\.BruteForceAgrees|VdsFileTest\.ByteFlipsAreRefusedOrHarmless|CapsLabelsEqualTheExactTermsNearOneHalf'
if configure core-only -DVDS_BUILD_TESTS=ON -DVDS_BUILD_GL=OFF "${unfindable[@]}" "${launcher[@]}"; then
  if ! cmake --build "$work/core-only" -j "$(nproc)" >"$work/core-only-build.log" 2>&1; then
    fail "core-only: build failed:"
    tail -n 40 "$work/core-only-build.log" >&2
  elif [ -n "$(find "$work/core-only" -name 'libvds_gl*' -o -name 'vds_*_tests' ! -name vds_core_tests ! -name vds_caps_tests ! -name vds_predicates_tests ! -name vds_interop_tests ! -name vds_vdb_tests)" ]; then
    fail "core-only: a GL library or GL test suite was built"
  elif ldd "$work/core-only/tests/vds_core_tests" | grep -E 'libEGL|libGL|libOpenGL|libpng'; then
    fail "core-only: the core suite loads GL or PNG"
  # The suite less its three slowest tests (over 5 s each; they run in the
  # main build), so this test stays around a minute on two cores.
  elif ! ctest --test-dir "$work/core-only" -LE build -E "$slow" -j "$(nproc)" --output-on-failure \
         >"$work/core-only-test.log" 2>&1; then
    fail "core-only: tests failed:"
    grep -E 'Failed|\*\*\*' "$work/core-only-test.log" >&2 || tail -n 40 "$work/core-only-test.log" >&2
  else
    grep -E 'tests passed|Total Test time' "$work/core-only-test.log"
  fi
fi

if [ "$failures" -ne 0 ]; then
  echo "configure_test: $failures failure(s)" >&2
  exit 1
fi
echo "configure_test: every option combination configures; core alone builds and passes its tests"
