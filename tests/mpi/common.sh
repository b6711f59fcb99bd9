# shellcheck shell=bash disable=SC2034  # sourced by the tests/mpi scripts, which use these
# Shared by the MPI study tests. Arguments come from CTest:
#   MPIEXEC MDRMAP PYRUN SRCDIR WORKDIR
# Oversubscription and running as root are allowed here, for the tests only.
set -euo pipefail
MPIEXEC=$1 MDRMAP=$2 PYRUN=$3 SRCDIR=$4 WORKDIR=$5
shift 5
export OMPI_MCA_rmaps_base_oversubscribe=1
if [[ "$(id -u)" == 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
mkdir -p "$WORKDIR"
CHECK=("$PYRUN" "$SRCDIR/tools/maps/check_map.py")
COMPARE=("$PYRUN" "$SRCDIR/tools/maps/compare_maps.py")
study() { # study NP ARGS...: runs mdrmap study on NP ranks, quiet
  local np=$1
  shift
  "$MPIEXEC" -np "$np" "$MDRMAP" study --quiet "$@"
}
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
