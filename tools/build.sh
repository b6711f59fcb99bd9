#!/usr/bin/env bash
# Configures and builds mdrmap with CMake, using every core.
#
#   bash tools/build.sh [extra cmake configure arguments...]
#   e.g. bash tools/build.sh -DMDRMAP_BUILD_TESTS=OFF
#
# Environment:
#   BUILD_DIR=build       build directory (relative to the repository root, or absolute)
#   BUILD_TYPE=Release    CMAKE_BUILD_TYPE (Release, Debug, RelWithDebInfo, ...)
#   BUILD_TARGETS="..."   build only these targets (space-separated; default: all)
#   JOBS=$(nproc)         parallel build jobs
#   CI=true               adds -DMDRMAP_WERROR=ON (warnings are errors)
#   CCACHE_BASEDIR=ROOT   ccache's base directory (the repository root by default)
# Compiles through ccache when it is installed (tools/setup.sh installs it;
# -DCMAKE_CXX_COMPILER_LAUNCHER= turns it off).
# Does not install packages: tools/setup.sh does (tools/test.sh runs both).
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"

BUILD_DIR=${BUILD_DIR:-build}
BUILD_TYPE=${BUILD_TYPE:-Release}
JOBS=${JOBS:-$(nproc 2>/dev/null || echo 2)}

config=(-S "$ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE="$BUILD_TYPE")
if [[ "${CI:-}" == true ]]; then
  config+=(-DMDRMAP_WERROR=ON)
fi
if command -v ccache >/dev/null 2>&1; then
  config+=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$ROOT}
fi
config+=("$@") # last -D wins: the caller's arguments override the defaults above

echo "build: cmake ${config[*]}" >&2
cmake "${config[@]}"

build=(--build "$BUILD_DIR" --parallel "$JOBS")
if [[ -n "${BUILD_TARGETS:-}" ]]; then
  read -r -a targets <<<"$BUILD_TARGETS"
  build+=(--target "${targets[@]}")
fi
echo "build: cmake ${build[*]}" >&2
cmake "${build[@]}"
