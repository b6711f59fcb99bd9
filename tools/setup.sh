#!/usr/bin/env bash
# Installs the Debian/Ubuntu packages that mdrmap's build, tests and tools need.
#
#   bash tools/setup.sh
#
# Does nothing when every package is already installed (no apt-get update).
# Otherwise: as root it runs apt-get itself; as a user it uses sudo if sudo
# works without a password prompt; failing that it prints the command to run
# and exits 1. Never reads standard input.
#
# Environment:
#   MDRMAP_SKIP_SETUP=1   skip the check entirely (non-Debian systems, modules,
#                         Spack, ... : then CMake finds the dependencies itself)
set -euo pipefail

PACKAGES=(
  # toolchain
  g++ make cmake git clang-format
  # MPI and parallel HDF5
  libopenmpi-dev openmpi-bin libhdf5-openmpi-dev hdf5-tools
  # C++ libraries
  libboost-program-options-dev libgtest-dev libbenchmark-dev
  # post-processing (tools/*.py)
  python3-numpy python3-h5py python3-matplotlib
  # profiling in tools/bench.sh; linting the job scripts in the tests
  valgrind shellcheck
)

log() { printf 'setup: %s\n' "$*" >&2; }

if [[ "${MDRMAP_SKIP_SETUP:-0}" == 1 ]]; then
  log "MDRMAP_SKIP_SETUP=1: not checking system packages"
  exit 0
fi

if ! command -v dpkg-query >/dev/null 2>&1; then
  log "not a Debian/Ubuntu system (no dpkg-query): not checking packages."
  log "mdrmap needs: a C++17 compiler, CMake >= 3.18, MPI, parallel HDF5 (MPI-IO),"
  log "Boost.Program_options, GoogleTest; set MDRMAP_SKIP_SETUP=1 to silence this."
  exit 0
fi

missing=()
for pkg in "${PACKAGES[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
  if [[ "$status" != "install ok installed" ]]; then
    missing+=("$pkg")
  fi
done

if ((${#missing[@]} == 0)); then
  log "all ${#PACKAGES[@]} required packages are installed"
  exit 0
fi

log "missing packages: ${missing[*]}"

apt_install=(apt-get -o DPkg::Lock::Timeout=600 install -y --no-install-recommends "${missing[@]}")

if [[ "$(id -u)" == 0 ]]; then
  sudo_cmd=()
elif command -v sudo >/dev/null 2>&1 && sudo -n true </dev/null >/dev/null 2>&1; then
  sudo_cmd=(sudo -n)
else
  log "not root and no password-less sudo: please install them with"
  printf '\n  sudo apt-get update && sudo apt-get install -y --no-install-recommends %s\n\n' \
    "${missing[*]}" >&2
  exit 1
fi

export DEBIAN_FRONTEND=noninteractive
log "running apt-get update"
${sudo_cmd[@]+"${sudo_cmd[@]}"} apt-get -o DPkg::Lock::Timeout=600 update </dev/null
log "running ${apt_install[*]}"
${sudo_cmd[@]+"${sudo_cmd[@]}"} env DEBIAN_FRONTEND=noninteractive "${apt_install[@]}" </dev/null
log "done"
