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
#   MDRMAP_SLURM=1        also Slurm (slurmctld slurmd slurm-client munge) and its
#                         PBS wrappers (slurm-wlm-torque), for the tests that run
#                         the job scripts under a real one-node Slurm (label
#                         slurm; skipped without them). Default: 1 when CI=true.
#                         The daemons are not started here (the tests start
#                         their own); mpirun/mpiexec stay Open MPI's.
set -euo pipefail

PACKAGES=(
  # toolchain (ccache: tools/test.sh compiles through it, so that the test
  # install_pip, a second build of the program and module from a copy of the
  # source, finds the first build's objects)
  g++ make cmake git clang-format ccache
  # MPI and parallel HDF5
  libopenmpi-dev openmpi-bin libhdf5-openmpi-dev hdf5-tools
  # C++ libraries
  libboost-program-options-dev libgtest-dev libbenchmark-dev
  # mdrmap fit: the least-squares solver (find_package(Ceres))
  libceres-dev
  # post-processing (python -m mdrmap TOOL, tools/*.py; the tool mapxr: xarray;
  # Result.to_dataframe: pandas, optional)
  python3-numpy python3-h5py python3-matplotlib python3-xarray python3-h5netcdf
  # the Python module (src/python: pybind11) and its tests and examples
  pybind11-dev python3-dev python3-pytest python3-scipy
  # pip install . (pyproject.toml: setuptools driving CMake) into a venv
  python3-pip python3-venv python3-setuptools python3-wheel
  # profiling in tools/bench.sh; linting the job scripts in the tests
  valgrind shellcheck
  # the user guide under docs/ (Sphinx, MyST Markdown, the furo theme; test docs_site)
  python3-sphinx python3-myst-parser furo
)
SLURM_PACKAGES=(slurmctld slurmd slurm-client munge slurm-wlm-torque)
if [[ "${MDRMAP_SLURM:-}" == 1 || ( -z "${MDRMAP_SLURM:-}" && "${CI:-}" == true ) ]]; then
  PACKAGES+=("${SLURM_PACKAGES[@]}")
fi

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

# slurm-wlm-torque registers Slurm's mpiexec.slurm as an alternative for
# mpirun and mpiexec (below Open MPI's priority, but a manual choice or an
# install order may still pick it): pin them to Open MPI's launcher.
pin_mpirun() {
  [[ "$(id -u)" == 0 && -x /usr/bin/mpirun.openmpi ]] || return 0
  [[ "$(dpkg-query -W -f='${Status}' slurm-wlm-torque 2>/dev/null)" == "install ok installed" ]] ||
    return 0
  [[ "$(readlink -f /usr/bin/mpirun)" == "$(readlink -f /usr/bin/mpirun.openmpi)" &&
    "$(readlink -f /usr/bin/mpiexec)" == "$(readlink -f /usr/bin/mpiexec.openmpi)" ]] && return 0
  log "pinning mpirun/mpiexec to Open MPI's (slurm-wlm-torque offers mpiexec.slurm)"
  update-alternatives --set mpirun /usr/bin/mpirun.openmpi >&2 || true
}

if ((${#missing[@]} == 0)); then
  pin_mpirun
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
pin_mpirun
log "done"
