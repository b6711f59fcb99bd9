#!/usr/bin/env bash
# test_pbs.sh MDRMAP_EXE SRCDIR WORKDIR: jobs/study.pbs through Slurm's PBS
# wrappers (Debian's slurm-wlm-torque: qsub, qstat and the spank_pbs plugin
# that sets PBS_JOBID, PBS_O_WORKDIR, ...), on a one-node Slurm (cluster.sh),
# submitted with qsub by a user who is not root (uid 65534), as far as it goes:
#   the job's own timer (the wall time from 'qstat -f') stops the study
#   STOP_MARGIN s before the wall time; the job resubmits itself with
#   'qsub -W depend=afterany:JOB -v ...'; the chain of jobs (each a new job
#   ID) completes the map, identical to an uninterrupted run.
# No PBS server is in Debian, so what only a real PBS shows (its own qsub
# -v/-j handling, kill_delay, Torque's PBS_WALLTIME, qsig, qdel) stays with the
# stub tests (tests/jobs/test_jobs.sh). Exit 77 (a skip, with the reason) when
# not root, or the wrappers, the plugin or setpriv are missing, or the daemons
# do not start.
set -euo pipefail
(($# == 3)) || {
  echo "usage: $0 MDRMAP_EXE SRCDIR WORKDIR" >&2
  exit 2
}
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
MDRMAP_EXE=$(realpath "$1")
SRCDIR=$(cd "$2" && pwd)
# shellcheck source-path=SCRIPTDIR source=common.sh
source "$HERE/common.sh"
mkdir -p "$3"
WORK=$(cd "$3" && pwd)/pbs

command -v setpriv >/dev/null || skip "setpriv (util-linux) is needed to submit as uid 65534"
qsub=$(command -v qsub) || skip "no qsub: Slurm's PBS wrappers come with slurm-wlm-torque" \
  "('MDRMAP_SLURM=1 bash tools/setup.sh' installs them)"
grep -q sbatch "$qsub" 2>/dev/null || skip "$qsub is not Slurm's PBS wrapper (slurm-wlm-torque)"
plugin=""
for p in /usr/lib/*/slurm-wlm/spank_pbs.so /usr/lib/slurm-wlm/spank_pbs.so /usr/lib*/slurm/spank_pbs.so; do
  [[ -f "$p" ]] && plugin=$p && break
done
[[ -n "$plugin" ]] || skip "no spank_pbs.so (slurm-wlm-torque): PBS_* variables cannot be set"

rm -rf "$WORK"
mkdir -p "$WORK"
# What the user (uid 65534) runs and writes, in a directory that user can
# reach whatever the mode of the checkout and build directories: the binary,
# the job scripts and a work directory of its own.
STAGE=$(mktemp -d /tmp/mdrmap-pbs.XXXXXX)
scratch+=("$STAGE")
# shellcheck disable=SC2317 # called by stop_cluster
on_exit() { # on_exit RC: show the chain's logs on failure; keep them beside the test output
  local f
  if (($1 != 0 && $1 != 77)); then
    for f in "$STAGE"/run/study.pbs.[oe]*; do
      [[ -f "$f" ]] && echo "--- $f" >&2 && cat "$f" >&2
    done
  fi
  cp "$STAGE"/run/study.pbs.[oe]* "$WORK/" 2>/dev/null || true
}
mkdir -p "$STAGE/bin" "$STAGE/run"
cp "$MDRMAP_EXE" "$STAGE/bin/mdrmap"
cp "$(dirname "$MDRMAP_EXE")/mdrmap-study" "$STAGE/bin/" # (which mdrmap study runs)
cp -r "$SRCDIR/jobs" "$STAGE/jobs"
# the resources in the #PBS lines, as a user edits them (sbatch reads #PBS
# lines itself: -l select=...:ncpus=32 would ask for 32 CPUs on one node)
# and every resubmitted job gets the header's resources, not the first qsub's
# options: a wall time of 1 minute there)
sed -i -e 's/^#PBS -l select=1:ncpus=32:mpiprocs=32$/#PBS -l select=1:ncpus=2:mpiprocs=2/' \
  -e 's/^#PBS -l walltime=04:00:00$/#PBS -l walltime=00:01:00/' "$STAGE/jobs/study.pbs"
[[ $(grep -cE '^#PBS -l (select=1:ncpus=2:mpiprocs=2|walltime=00:01:00)$' "$STAGE/jobs/study.pbs") == 2 ]] ||
  fail "jobs/study.pbs lacks the '#PBS -l select=1:ncpus=32:mpiprocs=32' or 'walltime=04:00:00' line"
cp "$SRCDIR/tests/jobs/small.ini" "$STAGE/run/study.ini" # 2240 cases, about 2 s at 2 ranks
chmod -R a+rX "$STAGE"
chown -R 65534:65534 "$STAGE/run"
user=(setpriv --reuid=65534 --regid=65534 --clear-groups)
"${user[@]}" test -x "$STAGE/bin/mdrmap" -a -w "$STAGE/run" ||
  fail "uid 65534 cannot run $STAGE/bin/mdrmap or write $STAGE/run"

start_cluster none "required $plugin"
pass "one-node Slurm with spank_pbs started"

# the reference: the same study, uninterrupted, without a scheduler
export OMPI_MCA_rmaps_base_oversubscribe=1
(cd "$WORK" && OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 \
  mpirun -np 2 "$MDRMAP_EXE" study --quiet --config "$STAGE/run/study.ini" --output ref.h5) ||
  fail "the reference study failed"
pass "reference map (mpirun -np 2, no scheduler)"

# The chain: a wall time of 1 minute (the header) and STOP_MARGIN=50: each
# job's timer stops the study after about 10 s, and the job resubmits itself.
# The first job's ranks are paused until its timer fired, so that it surely
# is interrupted; the next job completes the map (or more jobs, under load).
t=$SECONDS
first=$(cd "$STAGE/run" && "${user[@]}" env HOME="$STAGE/run" \
  CONFIG=study.ini OUTPUT=out/pbs.h5 MDRMAP="$STAGE/bin/mdrmap" NP=2 STOP_MARGIN=50 \
  JOB_SCRIPT="$STAGE/jobs/study.pbs" MAX_REQUEUES=20 \
  qsub \
  -v CONFIG,OUTPUT,MDRMAP,NP,STOP_MARGIN,JOB_SCRIPT,MAX_REQUEUES "$STAGE/jobs/study.pbs") ||
  fail "qsub as uid 65534 failed: $first"
echo "   first job: $first (uid 65534)"
map=$STAGE/run/out/pbs.h5
wait_open "job $first" "$map" none
sleep 0.2
pause "job $first" "$first"
for ((i = 0; i < 500; i++)); do
  grep -qs "SIGUSR1 received" "$STAGE/run/study.pbs.e$first" && break
  sleep 0.2
done
resume
grep -qs "SIGUSR1 received" "$STAGE/run/study.pbs.e$first" || fail "job $first: no timer in 100 s"

# wait (at most 5 minutes) until no job of the chain is left in the queue
for ((i = 0; i < 1500; i++)); do
  [[ -z "$(squeue -h -u 65534 -o %i 2>/dev/null)" ]] && break
  sleep 0.2
done
[[ -z "$(squeue -h -u 65534 -o %i)" ]] || fail "the chain still runs after 5 minutes"
mapfile -t jobs < <(scontrol show job -o 2>/dev/null | grep -o 'JobId=[0-9]*' | cut -d= -f2)
states=""
for j in "${jobs[@]}"; do
  states+=" $j:$(scontrol show job "$j" | tr ' ' '\n' | sed -n 's/^JobState=//p')/$(
    scontrol show job "$j" | tr ' ' '\n' | sed -n 's/^ExitCode=//p')"
done
echo "   jobs (state/exit code):$states"
((${#jobs[@]} >= 2)) || fail "no resubmission: ${#jobs[@]} job(s)"
# the wrapper names the logs after the script: study.pbs.o<id> and .e<id>
# (#PBS -j oe is not read: the script's messages are in the .e files)
logs=("$STAGE"/run/study.pbs.[oe]*)
grep -q "the map is complete" "${logs[@]}" 2>/dev/null ||
  fail "no job of the chain completed the map"
grep -q "PBS job $first on " "${logs[@]}" || fail "the first job did not run under PBS (spank_pbs)"
grep -qE "wall time 60 s: the study will be stopped in [0-9]+ s" "${logs[@]}" ||
  fail "no timer from the wall time of 'qstat -f'"
grep -q "resubmitted as job .* (resubmission 1 of at most 20)" "${logs[@]}" ||
  fail "no resubmission"
[[ " $states" == *" ${jobs[-1]}:COMPLETED/0:0"* ]] || fail "the last job did not complete: $states"
"$PYRUN" "$SRCDIR/tools/maps/check_map.py" --quiet --complete "$map" || fail "the map is not complete"
"$PYRUN" "$SRCDIR/tools/maps/compare_maps.py" "$WORK/ref.h5" "$map" >/dev/null ||
  fail "the map made by the chain differs from the uninterrupted run's"
[[ "$(stat -c %u "$map")" == 65534 ]] || fail "the map is not owned by uid 65534"
pass "study.pbs via qsub as uid 65534: ${#jobs[@]} jobs, timer, resubmission, the last COMPLETED," \
  "map identical to the reference ($((SECONDS - t)) s)"
echo "PASS: jobs/study.pbs through Slurm's PBS wrappers ($((SECONDS - t_start)) s)"
