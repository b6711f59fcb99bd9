#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite; exits non-zero on any failure.
#
#   bash tools/test.sh [extra ctest arguments...]
#   e.g. bash tools/test.sh -R Exact       # only tests whose name matches
#
# Two stages, both must pass: (1) the whole suite in BUILD_DIR; (2) the unit
# tests (ctest label "unit": test_core, test_study, test_cli and the mdrmap
# binary it runs) in a second build with AddressSanitizer and
# UndefinedBehaviorSanitizer (-DMDRMAP_SANITIZE=ON, RelWithDebInfo), where any
# sanitizer report fails the test. The ctest arguments apply to both stages.
#
# Environment: as tools/build.sh (BUILD_DIR, BUILD_TYPE, JOBS, CI), and
#   CMAKE_ARGS="..."            extra cmake configure arguments (space-separated; both builds)
#   SANITIZE=0                  skip stage 2 (default 1)
#   ASAN_BUILD_DIR=build-asan   build directory of stage 2
#   ASAN_OPTIONS, UBSAN_OPTIONS, LSAN_OPTIONS   appended to stage 2's settings
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"

BUILD_DIR=${BUILD_DIR:-build}
export BUILD_DIR
JOBS=${JOBS:-$(nproc 2>/dev/null || echo 2)}

bash tools/setup.sh
read -r -a cmake_args <<<"${CMAKE_ARGS:-}"
# tools/build.sh compiles through ccache with the paths below the root made
# relative (CCACHE_BASEDIR): the test install_pip builds the program and the
# module again from a copy of this tree under BUILD_DIR, whose compilations
# are then the first build's (cache hits), with the same setting.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$ROOT}
bash tools/build.sh ${cmake_args[@]+"${cmake_args[@]}"}

# MPI tests start several ranks on one small machine: allow more ranks than
# cores. Open MPI refuses to run as root unless told; CI runs as root. These
# settings belong to the test run only, never to the library or the user's jobs.
export OMPI_MCA_rmaps_base_oversubscribe=${OMPI_MCA_rmaps_base_oversubscribe:-1}
if [[ "$(id -u)" == 0 ]]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi

echo "test: ctest --output-on-failure -j $JOBS --no-tests=error $* (in $BUILD_DIR)" >&2
(cd "$BUILD_DIR" && ctest --output-on-failure -j "$JOBS" --no-tests=error "$@")

if [[ "${SANITIZE:-1}" == 0 ]]; then
  echo "test: SANITIZE=0: not running the unit tests under ASan+UBSan" >&2
  exit 0
fi

ASAN_BUILD_DIR=${ASAN_BUILD_DIR:-build-asan}
echo "== unit tests under ASan+UBSan (in $ASAN_BUILD_DIR)" >&2
# Only what the unit tests need (the target unit_tests: no benchmark, case
# sets, MPI-only tests); warnings are errors under CI as in stage 1. Debug
# information of lines only (-g1: a report's stack names functions, files and
# lines; no variables, which -g adds for a fifth more compile time). The
# caller's CMAKE_ARGS come first: the sanitizer switch wins.
BUILD_DIR=$ASAN_BUILD_DIR BUILD_TYPE=RelWithDebInfo BUILD_TARGETS=unit_tests \
  bash tools/build.sh "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1 -DNDEBUG" \
  ${cmake_args[@]+"${cmake_args[@]}"} \
  -DMDRMAP_SANITIZE=ON -DMDRMAP_BUILD_TESTS=ON -DMDRMAP_BUILD_BENCH=OFF
# Every unit test of stage 1 is there (an executable missing from unit_tests
# would leave its tests unlisted, i.e. silently not run).
unit_list() { (cd "$1" && ctest -N -L unit | sed -n 's/^ *Test *#[0-9]*: //p' | sort); }
if ! diff <(unit_list "$BUILD_DIR") <(unit_list "$ASAN_BUILD_DIR") >&2; then
  echo "test: the unit tests of $ASAN_BUILD_DIR differ from $BUILD_DIR's (<): is an executable" \
    "missing from the target unit_tests (tests/CMakeLists.txt)?" >&2
  exit 1
fi

# Any report is fatal: ASan and LeakSanitizer abort, UBSan halts (the code is
# also built with -fno-sanitize-recover=all). Open MPI, which `mdrmap study`
# starts even to refuse a bad config, does not free everything it allocates:
# those leaks are suppressed by its entry points, which needs the slow but
# complete unwinder on malloc; that is set only for the tests that start mdrmap
# (label unit-cli), as it slows allocation-heavy tests tenfold.
supp=$(cd "$ASAN_BUILD_DIR" && pwd)/lsan_openmpi.supp
cat >"$supp" <<'EOF'
# Written by tools/test.sh: leaks inside Open MPI's MPI_Init / MPI_Finalize.
leak:PMPI_Init
leak:ompi_mpi_init
leak:ompi_mpi_finalize
EOF
asan=detect_leaks=1:abort_on_error=1:halt_on_error=1:strict_string_checks=1
asan+=:check_initialization_order=1:strict_init_order=1
export ASAN_OPTIONS=$asan${ASAN_OPTIONS:+:$ASAN_OPTIONS}
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}
export LSAN_OPTIONS=suppressions=$supp:print_suppressions=0${LSAN_OPTIONS:+:$LSAN_OPTIONS}

# With ctest arguments (e.g. -R Exact) the selection may hold no unit test.
no_tests=error
(($# == 0)) || no_tests=ignore
run_unit() { # run_unit CTEST-ARGS...: the unit tests of stage 2
  echo "test: ctest -L unit $* (in $ASAN_BUILD_DIR)" >&2
  (cd "$ASAN_BUILD_DIR" && ctest --output-on-failure -j "$JOBS" --no-tests="$no_tests" -L unit "$@")
}
run_unit -LE cli "$@"
ASAN_OPTIONS=$ASAN_OPTIONS:fast_unwind_on_malloc=0 run_unit -L cli "$@"
echo "test: the unit tests pass under ASan+UBSan" >&2
