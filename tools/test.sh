#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite; exits non-zero on any failure.
#
#   bash tools/test.sh [extra ctest arguments...]
#   e.g. bash tools/test.sh -R Exact       # only tests whose name matches
#
# Environment: as tools/build.sh (BUILD_DIR, BUILD_TYPE, JOBS, CI), and
#   CMAKE_ARGS="..."   extra cmake configure arguments (space-separated)
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"

BUILD_DIR=${BUILD_DIR:-build}
export BUILD_DIR
JOBS=${JOBS:-$(nproc 2>/dev/null || echo 2)}

bash tools/setup.sh
read -r -a cmake_args <<<"${CMAKE_ARGS:-}"
bash tools/build.sh ${cmake_args[@]+"${cmake_args[@]}"}

# MPI tests start several ranks on one small machine: allow more ranks than
# cores. Open MPI refuses to run as root unless told; CI runs as root. These
# settings belong to the test run only, never to the library or the user's jobs.
export OMPI_MCA_rmaps_base_oversubscribe=${OMPI_MCA_rmaps_base_oversubscribe:-1}
if [[ "$(id -u)" == 0 ]]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi

echo "test: ctest --output-on-failure -j $JOBS --no-tests=error $* (in $BUILD_DIR)" >&2
cd "$BUILD_DIR"
ctest --output-on-failure -j "$JOBS" --no-tests=error "$@"
