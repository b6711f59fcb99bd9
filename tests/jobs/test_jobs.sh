#!/usr/bin/env bash
# test_jobs.sh MDRMAP_EXE SRCDIR WORKDIR: the cluster job scripts jobs/study.sbatch
# and jobs/study.pbs, without Slurm or PBS.
#
#  1. Static: bash -n, shellcheck (when installed), the #SBATCH / #PBS header
#     lines (syntax, known options, values, all before the first command).
#  2. Each script outside a scheduler (mpirun, NP=2) on a 24-case config: a
#     complete map and its config copy; run again: resumed, nothing pending,
#     exit 0, results unchanged. Refusals: a file that is not a map, a map of
#     another study, a missing config (exit 2, file untouched).
#  3. Interruptions of a ~3 s study (4480 cases), signalled as the scheduler would, each
#     leaving a valid, resumable map with progress made:
#     study.sbatch: SIGUSR1 to the script alone (--signal=B:USR1) outside
#       Slurm (exit 3, "not requeued"); then under a fake Slurm (stub srun and
#       scontrol on PATH): requeued with 'scontrol requeue ID'; at
#       MAX_REQUEUES: not requeued; SIGTERM to the whole job (scancel): not
#       requeued.
#     study.pbs: under a fake PBS (stub mpiexec, qstat, qsub), on a map of its
#       own: the script's timer stops the study before the wall time, and the
#       job resubmits itself with its settings. Then SIGTERM to the whole job
#       (PBS at the wall time) outside PBS: exit 3; SIGTERM long before the
#       wall time (qdel) under the fake PBS: not resubmitted.
#     Then a last plain run of each completes its map; the two maps, each
#     assembled from several runs, must be identical.
# Uses mpirun on PATH; allows oversubscription for itself. The scripts must set
# Open MPI's run-as-root variables themselves for a local run, so they are
# unset here.
set -euo pipefail
(($# == 3)) || {
  echo "usage: $0 MDRMAP_EXE SRCDIR WORKDIR" >&2
  exit 2
}
[[ -x "$1" && -f "$2/jobs/study.sbatch" ]] || {
  echo "FAIL: no executable $1, or no jobs/study.sbatch in $2" >&2
  exit 1
}
SELF=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/$(basename "${BASH_SOURCE[0]}")
MDRMAP_EXE=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
SRCDIR=$(cd "$2" && pwd)
mkdir -p "$3"
WORK=$(cd "$3" && pwd)/jobs
SBATCH=$SRCDIR/jobs/study.sbatch
PBS=$SRCDIR/jobs/study.pbs
LIB=$SRCDIR/jobs/lib/study_job.sh
export OMPI_MCA_rmaps_base_oversubscribe=1
unset OMPI_ALLOW_RUN_AS_ROOT OMPI_ALLOW_RUN_AS_ROOT_CONFIRM
# no scheduler, and none of the scripts' settings, from the caller
while read -r v; do unset "$v"; done < <(compgen -e | grep -E '^(SLURM_|PBS_)' || true)
unset CONFIG OUTPUT MDRMAP EXTRA_ARGS NP LAUNCHER MAX_REQUEUES STOP_MARGIN WALLTIME \
  JOB_SCRIPT RESUBMIT_COUNT

rm -rf "$WORK"
mkdir -p "$WORK/bin"
cd "$WORK"
t_start=$SECONDS
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
pass() { echo "ok ($((SECONDS - t_start)) s): $*"; }
PYRUN=$SRCDIR/tools/pyrun
check_map() { "$PYRUN" "$SRCDIR/tools/maps/check_map.py" --quiet "$@" >/dev/null; }
compare_maps() { "$PYRUN" "$SRCDIR/tools/maps/compare_maps.py" "$@" >/dev/null; }
status() { "$PYRUN" "$(dirname "$SELF")/map_status.py" "$1"; }

# Background jobs of this test run in their own process groups; kill what is
# left on the way out.
groups=()
cleanup() {
  local g
  for g in ${groups[@]+"${groups[@]}"}; do kill -KILL -- "-$g" 2>/dev/null || true; done
}
trap cleanup EXIT

# ---- 1. static checks --------------------------------------------------------
for s in "$SBATCH" "$PBS" "$LIB"; do
  bash -n "$s" || fail "bash -n $s"
done
if command -v shellcheck >/dev/null 2>&1; then
  shellcheck -x "$SBATCH" "$PBS" "$LIB" "$SELF" || fail "shellcheck"
  pass "bash -n, shellcheck"
else
  echo "skip: shellcheck not installed (apt-get install shellcheck)"
  pass "bash -n"
fi

# header_lines FILE PREFIX: the directive lines; fails unless all of them come
# before the first command (the schedulers stop reading there)
header_lines() {
  awk -v p="$2" '
    NR == 1 { if ($0 !~ /^#!\/bin\/bash/) { print "no #!/bin/bash line" > "/dev/stderr"; bad = 1 }; next }
    /^[[:space:]]*$/ || /^#/ { if (index($0, p " ") == 1) { if (cmd) late = late " " NR; else print } ; next }
    { cmd = 1 }
    END { if (late) { print "directives after the first command, lines" late > "/dev/stderr"; bad = 1 }; exit bad }
  ' "$1"
}
sbatch_opts=" job-name nodes ntasks ntasks-per-node cpus-per-task time output error open-mode signal requeue partition account mem mem-per-cpu qos constraint exclusive mail-type mail-user "
sbatch_seen=" "
while IFS= read -r line; do
  [[ "$line" =~ ^#SBATCH\ --([a-z][a-z-]*)(=([^[:space:]]+))?$ ]] ||
    fail "malformed (want '#SBATCH --option[=value]'): $line"
  opt=${BASH_REMATCH[1]} val=${BASH_REMATCH[3]}
  [[ "$sbatch_opts" == *" $opt "* ]] || fail "unknown sbatch option: $line"
  sbatch_seen+="$opt "
  case $opt in
    nodes | ntasks | ntasks-per-node | cpus-per-task) [[ "$val" =~ ^[1-9][0-9]*$ ]] ;;
    time) [[ "$val" =~ ^([0-9]+-)?[0-9]+(:[0-5][0-9]){0,2}$ ]] ;;
    signal) [[ "$val" =~ ^B:USR1@([0-9]+)$ ]] ;;
    open-mode) [[ "$val" == append ]] ;;
    requeue) [[ -z "$val" ]] ;;
    job-name | output) [[ -n "$val" ]] ;;
    *) true ;;
  esac || fail "bad value: $line"
  if [[ $opt == time ]]; then
    IFS=: read -r -a hms <<<"${val#*-}"
    limit=0
    for x in "${hms[@]}"; do limit=$((limit * 60 + 10#$x)); done
  fi
  [[ $opt == signal ]] && warn=${val#*@}
done < <(header_lines "$SBATCH" "#SBATCH" || fail "$SBATCH header")
for opt in job-name nodes ntasks time output open-mode signal requeue; do
  [[ "$sbatch_seen" == *" $opt "* ]] || fail "no #SBATCH --$opt"
done
((warn < limit)) || fail "--signal time $warn s not below --time ($limit s)"

pbs_seen=" "
while IFS= read -r line; do
  [[ "$line" =~ ^#PBS\ -([A-Za-z])(\ ([^[:space:]]+))?$ ]] ||
    fail "malformed (want '#PBS -X [value]'): $line"
  opt=${BASH_REMATCH[1]} val=${BASH_REMATCH[3]}
  if [[ $opt == l ]]; then pbs_seen+="l:${val%%=*} "; else pbs_seen+="$opt "; fi
  case $opt in
    N) [[ "$val" =~ ^[A-Za-z][A-Za-z0-9_.-]{0,14}$ ]] ;;
    l) [[ "$val" =~ ^(walltime=[0-9]+:[0-5][0-9]:[0-5][0-9]|select=[1-9][0-9]*(:[a-z_]+=[A-Za-z0-9_.]+)+|nodes=[1-9][0-9]*(:ppn=[1-9][0-9]*)?|mem=[0-9]+[kmgt]?b)$ ]] ;;
    j) [[ "$val" =~ ^(oe|eo|n)$ ]] ;;
    r) [[ "$val" =~ ^[yn]$ ]] ;;
    S) [[ "$val" == /* ]] ;;
    q | A | o | e | m | M | W | v) [[ -n "$val" ]] ;;
    *) false ;;
  esac || fail "bad or unknown PBS directive: $line"
done < <(header_lines "$PBS" "#PBS" || fail "$PBS header")
for want in N l:walltime l:select j r S; do
  [[ "$pbs_seen" == *" $want "* ]] || fail "no #PBS -${want/:/ } directive"
done
# never --overwrite in a command of either script (comments may mention it)
! grep -vE '^[[:space:]]*#' "$SBATCH" "$PBS" | grep -q -- '--overwrite' ||
  fail "a job script passes --overwrite"
pass "#SBATCH and #PBS headers"

# ---- helpers ------------------------------------------------------------------
cat >tiny.ini <<'EOF'
; 24 cases, instant
[grid]
d = 1e-3
R = 1, 2
tau = 0.5, 2
v = logspace:1e-2:1e2:3
v1_over_v = 0.01, 2
[run]
samples = 21
EOF
cp "$(dirname "$SELF")/big.ini" big.ini # 4480 cases, about 3 s at 2 ranks, to be interrupted

# start NAME SCRIPT [VAR=VALUE...]: starts the job script in the background in
# its own process group (a job), log NAME.log; sets $job
start() {
  local name=$1 script=$2
  shift 2
  env MDRMAP="$MDRMAP_EXE" NP=2 "$@" setsid bash "$script" >"$name.log" 2>&1 &
  job=$!
  groups+=("$job")
}
# finish NAME: waits (at most 60 s) for $job; sets $rc
finish() {
  local i
  for ((i = 0; i < 1200; i++)); do
    kill -0 "$job" 2>/dev/null || break
    sleep 0.05
  done
  if kill -0 "$job" 2>/dev/null; then
    kill -KILL -- "-$job" 2>/dev/null || true
    cat "$1.log" >&2
    fail "$1: still running after 60 s"
  fi
  rc=0
  wait "$job" || rc=$?
}
# run NAME SCRIPT [VAR=VALUE...]: start + finish
run() {
  start "$@"
  finish "$1"
}
expect() { # expect NAME CODE PATTERN...: exit code and log lines (grep -E)
  local name=$1 code=$2 p
  shift 2
  [[ $rc == "$code" ]] || {
    cat "$name.log" >&2
    fail "$name: exit code $rc, expected $code"
  }
  for p in "$@"; do
    grep -qE -- "$p" "$name.log" || {
      cat "$name.log" >&2
      fail "$name: no line matching '$p' in the log"
    }
  done
}
stamp() { stat -c %y "$1" 2>/dev/null || echo none; } # modification time, in ns
# wait_for_work NAME MAP STAMP: until the study of $job has opened MAP (its
# modification time differs from STAMP, taken before the start: the ranks then
# catch signals), and a little longer so that it computes (at most 20 s)
wait_for_work() {
  local i
  for ((i = 0; i < 400; i++)); do
    if [[ "$(stamp "$2")" != "$3" ]]; then
      sleep 0.15
      return 0
    fi
    kill -0 "$job" 2>/dev/null || break
    sleep 0.05
  done
  cat "$1.log" >&2
  fail "$1: the study did not start"
}
progress=0
interrupted() { # interrupted NAME MAP: valid map, some cases done since the last call, some pending
  local d p
  check_map "$2" || fail "$1: map invalid after the interruption"
  read -r d p _ < <(status "$2")
  ((p > 0)) || fail "$1: nothing pending; the study ended before the signal (too fast a machine?)"
  ((d >= progress)) || fail "$1: fewer cases done than before ($d, $progress before)"
  echo "   $1: $d done, $p pending$( ((d > progress)) || echo " (no progress: a loaded machine?)")"
  progress=$d
}

# ---- 2. tiny study, fresh and resumed ------------------------------------------
for script in "$SBATCH" "$PBS"; do
  s=$(basename "$script")
  map=$WORK/tiny_$s.h5
  run "tiny_$s" "$script" CONFIG=tiny.ini OUTPUT="$map"
  expect "tiny_$s" 0 "new map $map" "mpirun -np 2 " "the map is complete"
  check_map --complete "$map" || fail "tiny_$s: map not complete"
  cmp -s tiny.ini "$map.config.ini" || fail "tiny_$s: no copy of the config next to the map"
  cp "$map" "$WORK/tiny_$s.first.h5"
  run "tiny_${s}_again" "$script" CONFIG=tiny.ini OUTPUT="$map"
  expect "tiny_${s}_again" 0 "resuming the map $map" "--output $map --resume" \
    "24 cases in .* 0 done, 0 failed this run \(24 done before\)" "the map is complete"
  check_map --complete "$map" || fail "tiny_${s}_again: map not complete"
  compare_maps "$WORK/tiny_$s.first.h5" "$map" || fail "tiny_${s}_again: the results changed"
  pass "$s: new map (complete, config copied), run again: resumed, nothing pending, unchanged"
done
compare_maps "$WORK/tiny_study.sbatch.h5" "$WORK/tiny_study.pbs.h5" ||
  fail "the two scripts made different maps"
# study.pbs in a Slurm job without PBS_JOBID (Slurm's qsub without spank_pbs)
run tiny_pbs_in_slurm "$PBS" CONFIG=tiny.ini OUTPUT="$WORK/tiny_study.pbs.h5" SLURM_JOB_ID=99
expect tiny_pbs_in_slurm 0 "warning: Slurm job 99 without PBS_JOBID .*nothing will be resubmitted"
pass "study.pbs in a Slurm job without PBS_JOBID: a warning"

# refusals: exit 2, file untouched, no requeue
echo "not a map" >notamap.h5
run refuse_file "$SBATCH" CONFIG=tiny.ini OUTPUT=notamap.h5
expect refuse_file 2 "is not an HDF5 map; not touching it"
[[ "$(cat notamap.h5)" == "not a map" ]] || fail "refuse_file: the file changed"
sum=$(sha256sum <"$WORK/tiny_study.pbs.h5")
run refuse_study "$PBS" CONFIG=big.ini OUTPUT="$WORK/tiny_study.pbs.h5"
expect refuse_study 2 "mdrmap refused"
! grep -qE "MPI_ABORT|mpirun detected|Primary job|^-{20}" refuse_study.log || {
  cat refuse_study.log >&2
  fail "refuse_study: the error line is buried under mpirun's abort banner (mpirun -q)"
}
! grep -qE "resubmitting|would run" refuse_study.log || fail "refuse_study: resubmits"
[[ "$(sha256sum <"$WORK/tiny_study.pbs.h5")" == "$sum" ]] || fail "refuse_study: the map changed"
run refuse_config "$SBATCH" CONFIG=missing.ini OUTPUT=x.h5
expect refuse_config 2 "CONFIG=missing.ini: no such file"
[[ ! -e x.h5 ]] || fail "refuse_config: made an output"
pass "refusals: not a map, another study, no config (exit 2, untouched)"

# ---- 3. interruptions --------------------------------------------------------------
# fake schedulers: stubs record their calls in $STUB_LOG; the launchers run
# mpirun on 2 ranks (allowing root: that is the fake cluster's business)
cat >bin/srun <<'EOF'
#!/bin/bash
echo "srun $* OMPI_ALLOW_RUN_AS_ROOT=${OMPI_ALLOW_RUN_AS_ROOT:-unset}" >>"$STUB_LOG"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
np=2
while [[ $1 == -* ]]; do # the launcher's options: -n N, --ntasks N, --ntasks=N
  case $1 in
    --mpi=list) printf 'MPI plugin types are...\n\tpmix\n\tnone\n' && exit 0 ;;
    -n | --ntasks) np=$2 && shift ;;
    --ntasks=*) np=${1#*=} ;;
  esac
  shift
done
exec mpirun -np "$np" "$@"
EOF
sed 's/^echo "srun/echo "mpiexec/' bin/srun >bin/mpiexec
cat >bin/scontrol <<'EOF'
#!/bin/bash
echo "scontrol $*" >>"$STUB_LOG"
EOF
cat >bin/squeue <<'EOF'
#!/bin/bash
echo "squeue $*" >>"$STUB_LOG"
echo "${FAKE_TIMELIMIT:-4:00:00}"
EOF
cat >bin/qstat <<'EOF'
#!/bin/bash
echo "qstat $*" >>"$STUB_LOG"
[[ $1 == -f ]] && printf 'Job Id: %s\n    Resource_List.walltime = %s\n' "$2" "$FAKE_WALLTIME"
EOF
cat >bin/qsub <<'EOF'
#!/bin/bash
echo "qsub $*" >>"$STUB_LOG"
while (($#)); do
  if [[ $1 == -v ]]; then
    for v in ${2//,/ }; do echo "qsub-env $v=${!v}" >>"$STUB_LOG"; done
  fi
  shift
done
echo 778.fake
EOF
chmod +x bin/*
STUB_LOG=$WORK/stubs.log
fake_path=PATH=$WORK/bin:$PATH
export STUB_LOG
: >"$STUB_LOG"

# -- study.sbatch --
map=$WORK/big_sbatch.h5
before=$(stamp "$map")
start usr1_local "$SBATCH" CONFIG=big.ini OUTPUT="$map"
wait_for_work usr1_local "$map" "$before"
kill -USR1 "$job" # --signal=B:USR1: the batch shell only
finish usr1_local
expect usr1_local 3 "SIGUSR1 received" "SIGUSR1 to the ranks on this node" \
  "mdrmap study: interrupted" "not under Slurm, so not requeued .*scontrol requeue" \
  "run the same command again"
interrupted usr1_local "$map"
pass "study.sbatch, no Slurm: SIGUSR1 to the script reaches the ranks, exit 3, not requeued"

before=$(stamp "$map")
start usr1_slurm "$SBATCH" CONFIG=big.ini OUTPUT="$map" "$fake_path" SLURM_JOB_ID=4242 \
  SLURM_RESTART_COUNT=1 MAX_REQUEUES=2
wait_for_work usr1_slurm "$map" "$before"
kill -USR1 "$job"
finish usr1_slurm
expect usr1_slurm 3 "Slurm job 4242" "resuming the map" "SIGUSR1 to .*srun \(PID" \
  "running: srun --mpi=pmix --ntasks 2 " \
  "requeueing job 4242 \(restart 2 of at most 2\)"
grep -qx "scontrol requeue 4242" "$STUB_LOG" || fail "usr1_slurm: no 'scontrol requeue 4242'"
grep -q "^srun .*OMPI_ALLOW_RUN_AS_ROOT=unset" "$STUB_LOG" ||
  fail "usr1_slurm: the script set Open MPI's run-as-root variables under Slurm"
grep -q "^srun .*mdrmap study --config .*big.ini --output $map --resume" "$STUB_LOG" ||
  fail "usr1_slurm: srun did not get the study with --resume"
interrupted usr1_slurm "$map"
: >"$STUB_LOG"
pass "study.sbatch, fake Slurm: srun, SIGUSR1 passed on, 'scontrol requeue 4242'"

before=$(stamp "$map")
start max_slurm "$SBATCH" CONFIG=big.ini OUTPUT="$map" "$fake_path" SLURM_JOB_ID=4242 \
  SLURM_RESTART_COUNT=2 MAX_REQUEUES=2 FAKE_TIMELIMIT=9:00
wait_for_work max_slurm "$map" "$before"
kill -USR1 "$job"
finish max_slurm
# 540 s with the header's --signal=B:USR1@300: at most 180 s of work per run
expect max_slurm 3 "requeued 2 times already \(MAX_REQUEUES=2\): not requeued" \
  "warning: time limit 540 s, stop signal 300 s before it .* after 180 s of work or less.* at least 720 s"
! grep -q "scontrol requeue" "$STUB_LOG" || fail "max_slurm: requeued beyond MAX_REQUEUES"
interrupted max_slurm "$map"
pass "study.sbatch, fake Slurm: no requeue at MAX_REQUEUES; a warning for a short time limit"

: >"$STUB_LOG"
sum=$(sha256sum <"$map")
run np_slurm "$SBATCH" CONFIG=big.ini OUTPUT="$map" "$fake_path" SLURM_JOB_ID=4242 SLURM_NTASKS=1
expect np_slurm 2 "NP=2 ranks exceed the 1 tasks \(--ntasks\) of this job"
! grep -qE "^(srun .*mdrmap|scontrol requeue)" "$STUB_LOG" || fail "np_slurm: ran or requeued"
[[ "$(sha256sum <"$map")" == "$sum" ]] || fail "np_slurm: the map changed"
! grep -q "warning: time limit" usr1_slurm.log || fail "usr1_slurm: a time warning for 4 h"
pass "study.sbatch, fake Slurm: more ranks than tasks refused (exit 2, not run, not requeued)"

before=$(stamp "$map")
start scancel_slurm "$SBATCH" CONFIG=big.ini OUTPUT="$map" "$fake_path" SLURM_JOB_ID=4242
wait_for_work scancel_slurm "$map" "$before"
kill -TERM -- "-$job" # scancel: every process of the job
finish scancel_slurm
expect scancel_slurm 3 "SIGTERM received" "cancelled or at the time limit .*not requeued"
! grep -q "scontrol requeue" "$STUB_LOG" || fail "scancel_slurm: requeued a cancelled job"
interrupted scancel_slurm "$map"
: >"$STUB_LOG"
pass "study.sbatch, fake Slurm: SIGTERM to the whole job (scancel): exit 3, not requeued"

run last_sbatch "$SBATCH" CONFIG=big.ini OUTPUT="$map"
expect last_sbatch 0 "resuming the map" "the map is complete"
check_map --complete "$map" || fail "last_sbatch: map not complete"
pass "study.sbatch: the next run completes the map"

# -- study.pbs --
# its own timer (the wall time from qstat -f; SECONDS counts whole seconds, so
# the timer fires after 1 or 2 s), on a map of its own, 4 times as large so
# that it surely outlasts the timer (it is never completed)
tmap=$WORK/big_timer.h5
bigger="--v1-over-v logspace:1e-4:0.9:100 --quiet"
start timer_pbs "$PBS" CONFIG=big.ini OUTPUT="$tmap" "$fake_path" PBS_JOBID=777.fake \
  PBS_O_WORKDIR="$WORK" JOB_SCRIPT="$PBS" FAKE_WALLTIME=00:00:03 STOP_MARGIN=1 \
  EXTRA_ARGS="$bigger"
finish timer_pbs
expect timer_pbs 3 "PBS job 777.fake" "wall time 3 s: the study will be stopped in [12] s" \
  "SIGUSR1 received" "SIGUSR1 to .*mpiexec \(PID" "resubmitted as job 778.fake"
grep -q "^qsub -W depend=afterany:777.fake -v .* $PBS\$" "$STUB_LOG" ||
  fail "timer_pbs: not resubmitted as expected: $(grep '^qsub' "$STUB_LOG")"
for e in "CONFIG=big.ini" "OUTPUT=$tmap" "MDRMAP=$MDRMAP_EXE" "NP=2" "STOP_MARGIN=1" \
  "JOB_SCRIPT=$PBS" "EXTRA_ARGS=$bigger" "RESUBMIT_COUNT=1"; do
  grep -qxF "qsub-env $e" "$STUB_LOG" || fail "timer_pbs: the resubmitted job lacks $e"
done
# Open MPI's run-as-root variables: for a launcher that root runs, never else
if [[ "$(id -u)" == 0 ]]; then root_vars=1; else root_vars="unset"; fi
grep -q "^mpiexec .*OMPI_ALLOW_RUN_AS_ROOT=$root_vars\$" "$STUB_LOG" ||
  fail "timer_pbs: mpiexec got OMPI_ALLOW_RUN_AS_ROOT=$(sed -n 's/^mpiexec .*OMPI_ALLOW_RUN_AS_ROOT=//p' "$STUB_LOG"), expected $root_vars (uid $(id -u))"
progress=0
interrupted timer_pbs "$tmap"
: >"$STUB_LOG"
pass "study.pbs, fake PBS: own timer before the wall time, exit 3, resubmitted with its settings"

# a map interrupted twice, then completed
map=$WORK/big_pbs.h5
progress=0
before=$(stamp "$map")
start term_local "$PBS" CONFIG=big.ini OUTPUT="$map"
wait_for_work term_local "$map" "$before"
kill -TERM -- "-$job" # PBS at the wall time: every process of the job
finish term_local
expect term_local 3 "SIGTERM received" "not under PBS, so not resubmitted .*qsub" \
  "run the same command again"
interrupted term_local "$map"
pass "study.pbs, no PBS: SIGTERM to the whole job, exit 3 (even though mpirun says 1)"

before=$(stamp "$map")
start qdel_pbs "$PBS" CONFIG=big.ini OUTPUT="$map" "$fake_path" PBS_JOBID=777.fake \
  PBS_O_WORKDIR="$WORK" JOB_SCRIPT="$PBS" FAKE_WALLTIME=01:00:00
wait_for_work qdel_pbs "$map" "$before"
kill -TERM -- "-$job"
finish qdel_pbs
expect qdel_pbs 3 "cancelled \(SIGTERM before the wall time\): not resubmitted"
! grep -q "^qsub" "$STUB_LOG" || fail "qdel_pbs: resubmitted a cancelled job"
interrupted qdel_pbs "$map"
pass "study.pbs, fake PBS: SIGTERM long before the wall time (qdel): not resubmitted"

run last_pbs "$PBS" CONFIG=big.ini OUTPUT="$map"
expect last_pbs 0 "resuming the map" "the map is complete"
check_map --complete "$map" || fail "last_pbs: map not complete"
cmp -s big.ini "$map.config.ini" || fail "last_pbs: no copy of the config next to the map"
compare_maps "$WORK/big_sbatch.h5" "$map" ||
  fail "the maps assembled from interrupted runs differ"
pass "study.pbs: the next run completes the map; identical to study.sbatch's"

echo "PASS: job scripts ($((SECONDS - t_start)) s)"
