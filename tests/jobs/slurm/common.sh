# shellcheck shell=bash
# Shared by test_slurm.sh and test_pbs.sh (sourced after they set SRCDIR):
# messages, a clean environment, the one-node cluster's lifetime, and waits.
set -euo pipefail
PYRUN=$SRCDIR/tools/pyrun
CLUSTER=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/cluster.sh
t_start=$SECONDS
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
skip() {
  echo "SKIP: $*"
  exit 77
}
pass() { echo "ok ($((SECONDS - t_start)) s): $*"; }
[[ "$(id -u)" == 0 ]] || skip "a Slurm cluster of one's own needs root (slurmd runs jobs as their users)"

# nothing of the caller's scheduler, settings or Open MPI permissions: the job
# scripts must set what they need themselves (sbatch passes the environment on)
while read -r v; do unset "$v"; done < <(compgen -e | grep -E '^(SLURM_|SBATCH_|PBS_)' || true)
unset CONFIG OUTPUT MDRMAP EXTRA_ARGS NP LAUNCHER MAX_REQUEUES STOP_MARGIN WALLTIME \
  JOB_SCRIPT RESUBMIT_COUNT OMPI_ALLOW_RUN_AS_ROOT OMPI_ALLOW_RUN_AS_ROOT_CONFIRM

# start_cluster MPI_DEFAULT [PLUGSTACK_LINE]: a one-node Slurm in CL (short:
# munge's socket path), stopped by PID and removed on every way out (also the
# directories in $scratch); SLURM_CONF set. Exits 77 if it cannot start.
paused="" # PIDs of ranks stopped by the test: continued on the way out
scratch=()
CL=$(mktemp -d /tmp/mdrmap-slurm.XXXXXX)
stop_cluster() {
  local rc=$?
  # shellcheck disable=SC2086
  [[ -z "$paused" ]] || kill -CONT $paused 2>/dev/null || true
  bash "$CLUSTER" stop "$CL" || true
  if ((rc != 0 && rc != 77)); then
    echo "--- the end of slurmctld.log (the daemons' logs are kept in ${WORK:-?})" >&2
    tail -n 15 "$CL/slurmctld.log" >&2 2>/dev/null || true
    [[ -z "${WORK:-}" || ! -d "${WORK:-}" ]] || cp "$CL"/*.log "$WORK/" 2>/dev/null || true
  fi
  declare -F on_exit >/dev/null && on_exit "$rc"
  rm -rf "$CL" ${scratch[@]+"${scratch[@]}"}
  exit "$rc"
}
trap stop_cluster EXIT
start_cluster() {
  bash "$CLUSTER" start "$CL" "$@" || exit $?
  # shellcheck source=/dev/null
  source "$CL/env"
}

check_map() { "$PYRUN" "$SRCDIR/tools/maps/check_map.py" --quiet "$@" >/dev/null; }
compare_maps() { "$PYRUN" "$SRCDIR/tools/maps/compare_maps.py" "$@" >/dev/null; }
status() { "$PYRUN" "$SRCDIR/tests/jobs/map_status.py" "$1"; } # done pending failed
stamp() { stat -c %y "$1" 2>/dev/null || echo none; }          # modification time, in ns
# wait_open WHAT MAP STAMP: until a study has opened MAP (its modification time
# differs from STAMP; its ranks then catch signals), at most 120 s
wait_open() {
  local i
  for ((i = 0; i < 600; i++)); do
    [[ "$(stamp "$2")" == "$3" ]] || return 0
    sleep 0.2
  done
  fail "$1: the study did not open its map in 120 s"
}
ranks_of() { # ranks_of JID: the PIDs of the mdrmap processes of this cluster's job JID
  local p env
  for p in $(pgrep -x 'mdrmap(-study)?'); do # (a rank runs the study as mdrmap-study)
    env=$({ tr '\0' '\n' <"/proc/$p/environ"; } 2>/dev/null) || continue
    grep -qx "SLURM_JOB_ID=$1" <<<"$env" && grep -qxF "SLURM_CONF=$SLURM_CONF" <<<"$env" && echo "$p"
  done
  return 0
}
# pause WHAT JID: stops the job's ranks (SIGSTOP) so that the study is surely
# still running when a timed signal comes; resume continues them
pause() {
  paused=$(ranks_of "$2")
  [[ -n "$paused" ]] || fail "$1: no mdrmap process of job $2 found"
  # shellcheck disable=SC2086
  kill -STOP $paused
}
resume() {
  # shellcheck disable=SC2086
  kill -CONT $paused
  paused=""
}
