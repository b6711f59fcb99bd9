#!/usr/bin/env bash
# test_slurm.sh MDRMAP_EXE SRCDIR WORKDIR MPI_DEFAULT: jobs/study.sbatch under a
# real one-node Slurm (cluster.sh: munged, slurmctld, slurmd started by hand,
# MpiDefault=MPI_DEFAULT), submitted with sbatch as a user would. Each path
# checks the job's final state and its map:
#   A  complete: a new map, COMPLETED, exit 0; the reference map
#   B  wall time: --time=1 with SBATCH_SIGNAL=B:USR1@25 (the warning comes
#      with the first check of time limits after start + 5 s; the ranks are
#      paused until it came, so that the first run is surely interrupted):
#      SIGUSR1 -> exit 3 -> scontrol requeue -> the next run (same job ID,
#      restart 1) resumes -> COMPLETED, the map identical to A's
#   C  scancel (LAUNCHER=mpirun, as root: the run-as-root variables inside a
#      job): CANCELLED, not requeued, the map valid and incomplete
#   D  on C's map (it resumes it), MAX_REQUEUES=1: 'scancel --signal=USR1'
#      (the job steps, not the batch shell) -> exit 3 -> requeued; the second
#      run gets 'scancel --batch --signal=USR1' -> not requeued at the bound:
#      FAILED with exit code 3, the map valid and incomplete
#   E  a launcher that cannot start MPI (srun without PMIx under
#      MpiDefault=none; srun --mpi=none otherwise): FAILED, exit 1, not
#      requeued, a message that says what to set
#   F  (MpiDefault=none only) --ntasks larger than the node: sbatch --test-only
#      refuses it; submitted, it pends with Reason=PartitionConfig
#   G  (MpiDefault=none only) LAUNCHER=mpirun: 'scancel --signal=USR1' (no
#      --batch) reaches no rank (they run in the batch step): COMPLETED
# Exit 77 (a skip, with the reason) when not root or the Slurm packages are
# missing or the daemons do not start. Every wait is for a condition, with a
# generous timeout. The daemons are stopped by PID on every way out.
set -euo pipefail
(($# == 4)) || {
  echo "usage: $0 MDRMAP_EXE SRCDIR WORKDIR MPI_DEFAULT" >&2
  exit 2
}
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
MDRMAP_EXE=$(realpath "$1")
SRCDIR=$(cd "$2" && pwd)
MPI_DEFAULT=$4
# shellcheck source-path=SCRIPTDIR source=common.sh
source "$HERE/common.sh"
mkdir -p "$3"
WORK=$(cd "$3" && pwd)/slurm_$MPI_DEFAULT
SBATCH=$SRCDIR/jobs/study.sbatch
rm -rf "$WORK"
mkdir -p "$WORK"
cd "$WORK"
start_cluster "$MPI_DEFAULT"
pass "one-node Slurm started (MpiDefault=$MPI_DEFAULT)"
cp "$SRCDIR/tests/jobs/small.ini" small.ini # 2240 cases, about 2 s at 2 ranks
cp "$SRCDIR/tests/jobs/big.ini" big.ini     # 4480 cases, about 3-5 s at 2 ranks

# submit NAME [VAR=VALUE...] -- [SBATCH OPTIONS...]: sbatch jobs/study.sbatch
# from WORK with the settings in its environment; log NAME.log; sets $jid
submit() {
  local name=$1 vars=()
  shift
  while (($#)) && [[ $1 != -- ]]; do
    vars+=("$1")
    shift
  done
  shift
  jid=$(env MDRMAP="$MDRMAP_EXE" CONFIG=big.ini NP=2 ${vars[@]+"${vars[@]}"} \
    sbatch --parsable --job-name="$name" --output="$WORK/$name.log" --ntasks=2 "$@" "$SBATCH") ||
    fail "$name: sbatch refused the job"
  jid=${jid%%;*}
  echo "   $name: job $jid"
}
field() { # field JID NAME: a field of 'scontrol show job'
  scontrol show job "$1" 2>/dev/null | tr ' ' '\n' | sed -n "s/^$2=//p" | head -n 1
}
show_log() {
  echo "--- $1.log" >&2
  cat "$WORK/$1.log" >&2 2>/dev/null || true
}
# wait_state NAME JID REGEX SECONDS: until the job's state matches
wait_state() {
  local i state=""
  for ((i = 0; i < $4 * 5; i++)); do
    state=$(field "$2" JobState)
    [[ "$state" =~ ^($3)$ ]] && return 0
    sleep 0.2
  done
  show_log "$1"
  fail "$1: job $2 is '$state' after $4 s, expected $3"
}
# wait_log NAME PATTERN SECONDS [NTH]: until the log has NTH (default 1) lines matching
wait_log() {
  local i
  for ((i = 0; i < $3 * 5; i++)); do
    (($(grep -cE -- "$2" "$WORK/$1.log" 2>/dev/null || true) >= ${4:-1})) && return 0
    sleep 0.2
  done
  show_log "$1"
  fail "$1: no line matching '$2' in the log after $3 s"
}
expect_log() { # expect_log NAME PATTERN...: every pattern is in the log
  local name=$1 p
  shift
  for p in "$@"; do
    grep -qE -- "$p" "$WORK/$name.log" || {
      show_log "$name"
      fail "$name: no line matching '$p' in the log"
    }
  done
}
# expect_final NAME JID STATE EXIT RESTARTS: the job's final state and counts
# (EXIT: a regular expression)
expect_final() {
  local state code restarts
  wait_state "$1" "$2" "$3" 60
  code=$(field "$2" ExitCode)
  restarts=$(field "$2" Restarts)
  [[ "$code" =~ ^($4)$ && "$restarts" == "$5" ]] || {
    show_log "$1"
    fail "$1: ExitCode=$code Restarts=$restarts, expected $4 and $5"
  }
}
runs() { grep -cE "Slurm job $2 on .*, restart [0-9]+" "$WORK/$1.log" || true; }

# ---- A: a complete study --------------------------------------------------------
t=$SECONDS
submit complete OUTPUT=complete.h5 CONFIG=small.ini -- --time=15
wait_state complete "$jid" 'COMPLETED|FAILED|CANCELLED|TIMEOUT' 180
expect_final complete "$jid" COMPLETED 0:0 0
expect_log complete "new map $WORK/complete.h5" "running: srun --mpi=pmix " "the map is complete"
! grep -q "warning" complete.log || fail "complete: a warning for a 15-minute job: $(grep warning complete.log)"
check_map --complete complete.h5 || fail "complete: the map is not complete"
pass "A complete: COMPLETED, exit 0:0, srun --mpi=pmix, map complete ($((SECONDS - t)) s)"

# ---- B: the wall-time warning, requeue, resume, complete ----------------------------
t=$SECONDS
before=$(stamp walltime.h5)
submit walltime OUTPUT=walltime.h5 CONFIG=small.ini SBATCH_SIGNAL=B:USR1@25 MAX_REQUEUES=5 \
  -- --time=1
wait_open walltime walltime.h5 "$before"
sleep 0.2 # a few cases done before the pause
pause walltime "$jid"
wait_log walltime "SIGUSR1 received" 100
t_warn=$((SECONDS - t))
resume
wait_state walltime "$jid" 'COMPLETED|FAILED|CANCELLED|TIMEOUT' 300
n=$(runs walltime "$jid")
expect_final walltime "$jid" COMPLETED 0:0 $((n - 1))
((n >= 2)) || fail "walltime: $n run(s), expected at least 2"
expect_log walltime "warning: time limit 60 s, stop signal 25 s before it" \
  "SIGUSR1 to .*srun" "requeueing job $jid \(restart 1 of at most 5\)" \
  "Slurm job $jid on .*, restart 1 " "resuming the map $WORK/walltime.h5" \
  "mdrmap study: interrupted: .* the job resumes the map when it runs again" \
  "the map is complete"
check_map --complete walltime.h5 || fail "walltime: the map is not complete"
compare_maps complete.h5 walltime.h5 || fail "walltime: the map differs from the uninterrupted run's"
pass "B wall time: warning $t_warn s after submission, exit 3, requeued, $n runs, COMPLETED," \
  "map identical to A's ($((SECONDS - t)) s)"

# ---- C: scancel ---------------------------------------------------------------------
t=$SECONDS
before=$(stamp cancel.h5)
submit cancel OUTPUT=cancel.h5 LAUNCHER=mpirun -- --time=15
wait_open cancel cancel.h5 "$before"
sleep 0.3
scancel "$jid"
# the exit code is the script's (3) when it ended before KillWait, else 0:15
expect_final cancel "$jid" CANCELLED '3:0|0:15' 0
wait_log cancel "cancelled or at the time limit .*not requeued" 30
expect_log cancel "running: mpirun " "SIGTERM received"
! grep -q "requeueing" cancel.log || fail "cancel: requeued"
check_map cancel.h5 || fail "cancel: the map is not valid"
read -r d p _ < <(status cancel.h5)
((p > 0)) || fail "cancel: nothing pending (the study ended before scancel)"
pass "C scancel (mpirun as root inside the job): CANCELLED, not requeued, map valid ($d done," \
  "$p pending) ($((SECONDS - t)) s)"

# ---- D: scancel --signal=USR1, requeue, the MAX_REQUEUES bound -------------------------
t=$SECONDS
before=$(stamp cancel.h5)
submit bound OUTPUT=cancel.h5 MAX_REQUEUES=1 -- --time=15
wait_open bound cancel.h5 "$before"
before=$(stamp cancel.h5)
sleep 0.3
scancel --signal=USR1 "$jid" # the job steps (srun's tasks), not the batch shell
wait_log bound "requeueing job $jid \(restart 1 of at most 1\)" 60
wait_log bound "Slurm job $jid on .*, restart 1 " 120
wait_open bound cancel.h5 "$before"
sleep 0.3
scancel --batch --signal=USR1 "$jid" # the batch shell: the script passes it on
wait_state bound "$jid" 'COMPLETED|FAILED|CANCELLED|TIMEOUT' 120
expect_final bound "$jid" FAILED 3:0 1
expect_log bound "resuming the map $WORK/cancel.h5" \
  "requeued 1 times already \(MAX_REQUEUES=1\): not requeued"
[[ $(grep -c "resuming the map" bound.log) == 2 ]] || fail "bound: not 2 resumed runs"
check_map cancel.h5 || fail "bound: the map is not valid"
read -r d2 p _ < <(status cancel.h5)
((p > 0 && d2 > d)) || fail "bound: $d2 done (before: $d), $p pending"
pass "D scancel --signal=USR1: requeued; scancel --batch --signal=USR1 at MAX_REQUEUES=1:" \
  "FAILED 3:0, not requeued; map valid, resumed twice ($d2 done, $p pending) ($((SECONDS - t)) s)"

# ---- E: a launcher that cannot start MPI ---------------------------------------------------
t=$SECONDS
if [[ $MPI_DEFAULT == none ]]; then bad=srun; else bad="srun --mpi=none"; fi
submit nompi OUTPUT=nompi.h5 LAUNCHER="$bad" -- --time=15
wait_state nompi "$jid" 'COMPLETED|FAILED|CANCELLED|TIMEOUT' 120
expect_final nompi "$jid" FAILED 1:0 0
expect_log nompi "the study did not start .*the map was not opened.*set LAUNCHER='srun --mpi=pmix'.*Not requeued"
! grep -q "requeueing" nompi.log || fail "nompi: requeued"
pass "E LAUNCHER='$bad': FAILED 1:0, not requeued, says to set LAUNCHER ($((SECONDS - t)) s)"

# ---- F: more tasks than the node has ---------------------------------------------------------
if [[ $MPI_DEFAULT == none ]]; then
  t=$SECONDS
  cpus=$(sinfo -h -o %c | head -n 1)
  out=$(env MDRMAP="$MDRMAP_EXE" CONFIG=big.ini sbatch --test-only --nodes=1 \
    --ntasks=$((cpus + 1)) "$SBATCH" 2>&1) && fail "sbatch --test-only accepted $((cpus + 1)) tasks: $out"
  grep -q "Requested node configuration is not available" <<<"$out" ||
    fail "sbatch --test-only: $out"
  submit toobig OUTPUT=toobig.h5 -- --nodes=1 --ntasks=$((cpus + 1)) --time=15
  for ((i = 0; i < 150; i++)); do
    [[ "$(field "$jid" Reason)" == PartitionConfig ]] && break
    sleep 0.2
  done
  [[ "$(field "$jid" JobState)/$(field "$jid" Reason)" == PENDING/PartitionConfig ]] ||
    fail "toobig: $(field "$jid" JobState)/$(field "$jid" Reason), expected PENDING/PartitionConfig"
  scancel "$jid"
  pass "F --ntasks=$((cpus + 1)) on a $cpus-CPU node: sbatch --test-only refuses it," \
    "sbatch pends with Reason=PartitionConfig ($((SECONDS - t)) s)"
fi

# ---- G: scancel --signal=USR1 under mpirun ------------------------------------------------
if [[ $MPI_DEFAULT == none ]]; then
  t=$SECONDS
  before=$(stamp mpirun.h5)
  submit mpirun OUTPUT=mpirun.h5 LAUNCHER=mpirun -- --time=15
  wait_open mpirun mpirun.h5 "$before"
  sleep 0.3
  scancel --signal=USR1 "$jid"
  wait_state mpirun "$jid" 'COMPLETED|FAILED|CANCELLED|TIMEOUT' 180
  expect_final mpirun "$jid" COMPLETED 0:0 0
  ! grep -qE "SIGUSR1|interrupted" mpirun.log || fail "mpirun: the signal reached the study"
  check_map --complete mpirun.h5 || fail "mpirun: the map is not complete"
  pass "G LAUNCHER=mpirun: scancel --signal=USR1 (no --batch) reaches no rank; COMPLETED" \
    "($((SECONDS - t)) s)"
fi

echo "PASS: jobs/study.sbatch under a real Slurm, MpiDefault=$MPI_DEFAULT ($((SECONDS - t_start)) s)"
