# shellcheck shell=bash
# jobs/lib/study_job.sh: the logic that jobs/study.sbatch (Slurm) and
# jobs/study.pbs (PBS) share. Not a script of its own: each job script sets its
# settings (CONFIG OUTPUT MDRMAP EXTRA_ARGS NP LAUNCHER MAX_REQUEUES STOP_MARGIN
# WALLTIME, and JOB_SCRIPT for PBS) and `me`, sources this file and calls
#
#   study_job_main slurm|pbs
#
# which runs one `mdrmap study` and exits: 0 the map is complete; 3 the map is
# incomplete and resumable, whether or not the job was requeued (Slurm) or
# resubmitted (PBS) (the code describes the map, so that an 'afterok'
# dependency never starts on an incomplete map); 2 bad input or a refused
# output, not requeued (it would fail again); 1 any other failure.
# jobs/README.md explains it for users.

set -uo pipefail

STUDY_JOB_LIB_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
me=${me:-study job} # the script's name, for its messages

say() { echo "$me: $*" >&2; }
die() { # die CODE MESSAGE...
  local code=$1
  shift
  echo "$me: error: $*" >&2
  exit "$code"
}
now() { date '+%F %T'; }
abspath() { if [[ "$1" == /* ]]; then echo "$1"; else echo "$PWD/$1"; fi; }

# seconds TIME: [D-][[H:]M:]S (Slurm's and PBS's forms) in seconds (fractions
# dropped); fails on anything else (UNLIMITED, INVALID, empty)
seconds() {
  local part total=0 parts days=0 t=${1%.*}
  if [[ "$t" =~ ^([0-9]+)-(.*)$ ]]; then
    days=${BASH_REMATCH[1]} t=${BASH_REMATCH[2]}
  fi
  IFS=: read -r -a parts <<<"$t"
  ((${#parts[@]} >= 1 && ${#parts[@]} <= 3)) || return 1
  for part in "${parts[@]}"; do
    [[ "$part" =~ ^[0-9]+$ ]] || return 1
    total=$((total * 60 + 10#$part))
  done
  echo $((total + 10#$days * 86400))
}

# ---- signals --------------------------------------------------------------
# mdrmap stops cleanly (exit 3, map resumable) when its RANKS get SIGUSR1,
# SIGTERM or SIGINT. One rank is enough: rank 0 then hands out no more work,
# and every rank writes what it finished. The job script gets the warning
# (Slurm's --signal=B:USR1, the PBS script's own timer, qsig/scancel --batch)
# and passes it on, always as SIGUSR1:
#  * to the ranks on this node, found below the launcher (children of mpirun
#    or mpiexec, grandchildren under MPICH/Intel MPI's hydra proxy; srun has
#    none: its tasks belong to slurmstepd);
#  * under a scheduler, to the launcher too, which relays SIGUSR1 to the ranks
#    on every node (srun and Open MPI do; where a launcher does not, the ranks
#    on this node, rank 0 among them, are enough).
# Never SIGTERM to the launcher: srun answers its own SIGTERM by killing the
# tasks ("srun: forcing job termination"); Open MPI relays it but then reports
# exit code 1 instead of the ranks' 3. A local mpirun is signalled only when no
# rank is found below it yet. When the scheduler signals every process of the
# job (scancel, the time limit, qdel), the launcher gets SIGTERM anyway; the
# outcome is then judged by the signal this script received.
launcher=()
launcher_pid=""
signals="" # the signals received, e.g. " USR1"
ranks_below() { # ranks_below PID: the PIDs of the mdrmap processes below PID
  # (a rank starts as mdrmap and runs the study as mdrmap-study beside it, in
  # the same process: its name is either, cut to 15 characters)
  local child comm name
  comm=$(basename "$MDRMAP")
  for child in $(pgrep -P "$1" 2>/dev/null); do
    name=$(ps -o comm= -p "$child" 2>/dev/null)
    if [[ "$name" == "${comm:0:15}" || "$name" == mdrmap-study ]]; then
      echo "$child"
    else
      ranks_below "$child"
    fi
  done
}
stop_ranks() {
  local ranks=() targets=() what=""
  mapfile -t ranks < <(ranks_below "$launcher_pid")
  if ((${#ranks[@]})); then
    targets+=("${ranks[@]}")
    what="the ranks on this node (PID ${ranks[*]})"
  fi
  if [[ $mode != local ]] || ((${#ranks[@]} == 0)); then
    targets+=("$launcher_pid")
    what+="${what:+ and }${launcher[0]} (PID $launcher_pid)"
  fi
  say "asking the study to stop: SIGUSR1 to $what"
  kill -USR1 "${targets[@]}" 2>/dev/null
}
# shellcheck disable=SC2317 # called by the traps
on_signal() { # on_signal NAME
  signals+=" $1"
  say "$(now) SIG$1 received"
  [[ -z "$launcher_pid" ]] || stop_ranks
}

# ---- inputs -----------------------------------------------------------------
# Sets MDRMAP CONFIG OUTPUT (absolute), extra (EXTRA_ARGS split), resume
# (--resume or nothing); copies the config next to the map.
job_inputs() {
  local c
  if [[ -z "$MDRMAP" ]]; then
    # the submission directory first (Slurm and PBS run a copy of the job
    # script elsewhere), then the checkout this file belongs to, then the
    # prefix it is installed in (PREFIX/share/mdrmap/jobs/lib: PREFIX/bin)
    for c in "$PWD/build/src/mdrmap" "$STUDY_JOB_LIB_DIR/../../build/src/mdrmap" \
      "$STUDY_JOB_LIB_DIR/../../../../bin/mdrmap"; do
      if [[ -x "$c" ]]; then
        MDRMAP=$c
        break
      fi
    done
    [[ -n "$MDRMAP" ]] || MDRMAP=$(command -v mdrmap 2>/dev/null) ||
      die 2 "no mdrmap binary: build it (bash tools/build.sh) or set MDRMAP=/path/to/mdrmap"
  fi
  [[ -x "$MDRMAP" && ! -d "$MDRMAP" ]] || die 2 "MDRMAP=$MDRMAP is not an executable file"
  [[ -f "$CONFIG" ]] || die 2 "CONFIG=$CONFIG: no such file"
  CONFIG=$(abspath "$CONFIG")
  OUTPUT=$(abspath "$OUTPUT")
  MDRMAP=$(abspath "$MDRMAP")
  read -r -a extra <<<"$EXTRA_ARGS"
  mkdir -p "$(dirname "$OUTPUT")" || die 2 "cannot create the directory of OUTPUT=$OUTPUT"

  # Resume automatically: an existing HDF5 file gets --resume (mdrmap refuses,
  # with exit code 2 and without touching it, a file that is not an mdrmap map
  # or holds a different study); no file: a new map. Never --overwrite: only a
  # person replaces a map.
  resume=()
  if [[ -d "$OUTPUT" ]]; then
    die 2 "OUTPUT=$OUTPUT is a directory"
  elif [[ -e "$OUTPUT" ]]; then
    # the HDF5 signature \211HDF\r\n\032\n at offset 0
    [[ "$(od -An -tx1 -N8 "$OUTPUT" 2>/dev/null | tr -d ' \n')" == 894844460d0a1a0a ]] ||
      die 2 "$OUTPUT exists and is not an HDF5 map; not touching it" \
        "(move it away or choose another OUTPUT)"
    resume=(--resume)
  fi

  # Provenance: the config next to the map (the map stores its text too). A
  # resumed map keeps the copy made when it was created.
  local copy=$OUTPUT.config.ini
  if [[ ! -e "$copy" ]] || { ((${#resume[@]} == 0)) && ! cmp -s "$CONFIG" "$copy"; }; then
    cp "$CONFIG" "$copy" || die 1 "cannot copy the config to $copy"
  elif ! cmp -s "$CONFIG" "$copy"; then
    say "note: $CONFIG differs from $copy, the config the map was created with;" \
      "mdrmap refuses to resume a different study"
  fi
}

# ---- launcher ---------------------------------------------------------------
# Sets launcher (the default of the scheduler, else LAUNCHER) and cmd.
job_launcher() {
  local list
  case $mode in
    slurm)
      # srun starts MPI ranks through a PMI plugin. Open MPI (as Debian and
      # most sites build it) needs PMIx: where the site's MpiDefault is not
      # pmix, plain srun makes every rank fail in MPI_Init ("OMPI was not
      # built with SLURM's PMI support"). So ask for PMIx where srun offers it.
      launcher=(srun)
      if list=$(srun --mpi=list 2>&1) && grep -qE '(^|[[:space:]:])pmix([[:space:]_]|$)' <<<"$list"; then
        launcher+=(--mpi=pmix)
      else
        say "note: 'srun --mpi=list' offers no pmix: srun uses the site's MpiDefault;" \
          "if the ranks fail in MPI_Init, set LAUNCHER (e.g. LAUNCHER=mpirun)"
      fi
      [[ -z "$NP" ]] || launcher+=(--ntasks "$NP")
      ;;
    pbs)
      # mpiexec of a PBS-aware MPI (Open MPI with tm, hydra) finds the nodes itself
      launcher=(mpiexec)
      [[ -z "$NP" ]] || launcher+=(-n "$NP")
      ;;
    local)
      # -q (Open MPI's orte_execute_quiet, 4.x and 5.x): an error's one line
      # (exit 2) is not buried under mpirun's abort banner; the exit code stays
      launcher=(mpirun -np "${NP:-$(nproc 2>/dev/null || echo 1)}" -q)
      ;;
  esac
  [[ -z "$LAUNCHER" ]] || read -r -a launcher <<<"$LAUNCHER"
  command -v "${launcher[0]}" >/dev/null 2>&1 || die 1 "launcher '${launcher[0]}' not found on PATH"
  # Open MPI's mpirun refuses to run as root unless told to: set it for a
  # launcher that root runs (a local run, or a job of root's), never else.
  case $(basename "${launcher[0]}") in
    mpirun | mpiexec | orterun | mpirun.openmpi | mpiexec.openmpi)
      if [[ "$(id -u)" == 0 ]]; then
        export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
      fi
      ;;
  esac
  cmd=("${launcher[@]}" "$MDRMAP" study --config "$CONFIG" --output "$OUTPUT"
    ${resume[@]+"${resume[@]}"} ${extra[@]+"${extra[@]}"})
}

# ---- start-up checks ----------------------------------------------------------
# job_check_ranks SLOTS WHAT: NP must fit the job's SLOTS (tasks or slots);
# more ranks than the job has are refused (exit 2: srun and mpiexec would fail
# or oversubscribe the job's cores)
job_check_ranks() {
  [[ -n "$NP" && -n "$1" ]] || return 0
  [[ "$NP" =~ ^[1-9][0-9]*$ ]] || die 2 "NP=$NP is not a positive number of ranks"
  ((NP <= $1)) ||
    die 2 "NP=$NP ranks exceed the $1 $2 of this job: ask for at least $NP in the job's" \
      "resources, or lower NP; not requeued"
}
# job_check_time LIMIT MARGIN EARLY HOW: a warning when a run would spend less
# than half the time limit LIMIT (s) computing before the stop signal, which
# comes MARGIN s before the limit and up to EARLY s earlier still
job_check_time() {
  local limit=$1 margin=$2 early=$3 how=$4 work
  [[ -n "$limit" && -n "$margin" ]] || return 0
  work=$((limit - margin - early))
  ((2 * work < limit)) || return 0
  say "warning: time limit $limit s, stop $how: each run may be stopped after" \
    "$((work > 0 ? work : 0)) s of work or less, and every requeue (at most" \
    "$MAX_REQUEUES) waits in the queue again; ask for a time limit of at least" \
    "$((2 * (margin + early))) s, or a smaller stop margin"
}

# ---- run ------------------------------------------------------------------
# Runs cmd in the background and waits for it (bash runs a trap only between
# commands, so a launcher in the foreground would hold the signal back until
# the study ended by itself); a trapped signal makes 'wait' return early
# (status > 128): then wait again for the launcher's own status. Sets rc.
job_run() {
  local n_signals
  rc=0
  if [[ -n "$signals" ]]; then
    say "stopped before the study started"
    rc=3
    return
  fi
  "${cmd[@]}" &
  launcher_pid=$!
  [[ -z "$signals" ]] || stop_ranks # a signal came between the two lines above
  while true; do
    n_signals=${#signals}
    rc=0
    wait "$launcher_pid" || rc=$?
    ((${#signals} == n_signals)) && break # no trap ran: rc is the launcher's
  done
  launcher_pid=""
}

# stamp FILE: its modification time (none if missing)
stamp() { stat -c %y "$1" 2>/dev/null || echo none; }

# job_outcome AGAIN: exits unless the study was interrupted (rc 3, or any code
# after a signal); AGAIN is what the job does next ("requeued", "resubmitted")
job_outcome() {
  case $rc in
    0)
      # (srun may exit 0 when it could not launch the tasks at all; a
      # resumed map that was complete already is not written again)
      [[ -e "$OUTPUT" ]] ||
        die 1 "the launcher exited 0, but there is no map $OUTPUT (the ranks did not start?); not $1"
      say "$(now) the map is complete: $OUTPUT"
      exit 0
      ;;
    2)
      die 2 "mdrmap refused the input or the output (see above); not $1"
      ;;
    3) ;;
    *)
      # A launcher that got a signal itself reports a code of its own (Open MPI
      # 1, srun 128 + signal) even when the ranks stopped cleanly. The map
      # keeps every case marked done (mdrmap writes values first, status last).
      if [[ -z "$signals" ]]; then
        if [[ "$(stamp "$OUTPUT")" == "$map_stamp" ]]; then
          # the ranks never opened the map: they did not start, or not as MPI
          # ranks of one job
          local hint="check that LAUNCHER='${launcher[*]}' starts MPI programs of the MPI library mdrmap is built with (e.g. LAUNCHER=mpirun)"
          if [[ $(basename "${launcher[0]}") == srun && " ${launcher[*]} " != *" --mpi=pmix "* ]]; then
            hint="srun starts MPI ranks only through a PMI plugin that the MPI library supports: set LAUNCHER='srun --mpi=pmix' where 'srun --mpi=list' offers pmix (Open MPI), or LAUNCHER=mpirun"
          fi
          die "$rc" "the study did not start (exit code $rc, the map was not opened): the" \
            "launcher could not start the MPI ranks; $hint. Not $1."
        fi
        die "$rc" "the study failed (exit code $rc); not $1." \
          "The map keeps every finished case."
      fi
      say "the launcher exited with code $rc after a signal (${signals# }):" \
        "taking the study as interrupted"
      ;;
  esac
  say "$(now) interrupted; the map is resumable: $OUTPUT"
}

# ---- Slurm ------------------------------------------------------------------
# The stop margin: STOP_MARGIN, else the @ of --signal from SBATCH_SIGNAL (the
# environment of sbatch) or from the #SBATCH line of the submitted script (a
# --signal on the sbatch command line is not visible to the job).
slurm_margin() {
  local sig=${SBATCH_SIGNAL:-}
  if [[ -n "$STOP_MARGIN" ]]; then
    echo "$STOP_MARGIN"
    return
  fi
  [[ -n "$sig" ]] || sig=$(sed -n 's/^#SBATCH[[:space:]]*--signal[= ]\([^[:space:]]*\).*/\1/p' "$0" 2>/dev/null | tail -n 1)
  [[ "$sig" == *@* ]] && echo "${sig##*@}"
}
slurm_main() {
  local restarts=${SLURM_RESTART_COUNT:-0} limit margin tasks
  limit=$(seconds "$(squeue -h -j "$SLURM_JOB_ID" -o %l 2>/dev/null)") || limit=""
  margin=$(slurm_margin) || margin=""
  say "$(now) Slurm job $SLURM_JOB_ID on $(hostname), restart $restarts" \
    "(requeued at most $MAX_REQUEUES times)"
  tasks=${SLURM_NTASKS:-${SLURM_NPROCS:-}}
  job_check_ranks "$tasks" "tasks (--ntasks)"
  [[ -z "$margin" ]] ||
    job_check_time "$limit" "$margin" 60 "signal $margin s before it (--signal=B:USR1@$margin; Slurm may send it up to 60 s early)"
  job_start
  job_outcome requeued
  case " $signals " in
    *" TERM "* | *" INT "*)
      say "cancelled or at the time limit (SIGTERM/SIGINT): not requeued;" \
        "to continue, submit the job again: it resumes the map"
      exit 3
      ;;
  esac
  if ((restarts >= MAX_REQUEUES)); then
    say "requeued $restarts times already (MAX_REQUEUES=$MAX_REQUEUES): not requeued;" \
      "to continue, submit the job again: it resumes the map"
    exit 3
  fi
  # The requeue ends this run (Slurm kills what is left of it) and puts the job
  # back in the queue with the same job ID; its next run resumes the map. Slurm
  # starts it again no sooner than AuthInfo's cred_expire + 1 s (121 s by
  # default) after this run ends.
  trap '' USR1 TERM INT # nothing may interrupt the requeue (SIGKILL still can)
  say "requeueing job $SLURM_JOB_ID (restart $((restarts + 1)) of at most $MAX_REQUEUES)"
  scontrol requeue "$SLURM_JOB_ID" ||
    say "error: 'scontrol requeue $SLURM_JOB_ID' failed; to continue, submit the job again"
  exit 3
}

# ---- PBS --------------------------------------------------------------------
timer_pid=""
pbs_main() {
  local count=${RESUBMIT_COUNT:-0} walltime="" wt delay slots="" margin=${STOP_MARGIN:-300}
  # The wall time, in seconds (empty: unknown): WALLTIME, else Torque's
  # $PBS_WALLTIME, else Resource_List.walltime from 'qstat -f'.
  if [[ -n "$WALLTIME" ]]; then
    walltime=$(seconds "$WALLTIME") || die 2 "WALLTIME=$WALLTIME is not [[H:]M:]S"
  elif [[ $mode == pbs ]]; then
    wt=${PBS_WALLTIME:-$(qstat -f "$PBS_JOBID" 2>/dev/null |
      awk '$1 == "Resource_List.walltime" { print $3; exit }')}
    walltime=$(seconds "$wt") || walltime=""
  fi
  if [[ $mode == pbs ]]; then
    say "$(now) PBS job $PBS_JOBID on $(hostname), resubmission $count" \
      "(at most $MAX_REQUEUES)"
    if [[ -n "${PBS_NP:-}" ]]; then
      slots=$PBS_NP
    elif [[ -r "${PBS_NODEFILE:-}" ]]; then
      slots=$(grep -c . "$PBS_NODEFILE")
    fi
    job_check_ranks "$slots" "slots (PBS_NODEFILE)"
  else
    say "$(now) not under PBS: running on this machine ($(hostname))"
  fi
  job_check_time "$walltime" "$margin" 0 "timer $margin s before it (STOP_MARGIN)"

  # The warning timer: SIGUSR1 to this script STOP_MARGIN seconds before the
  # wall time (minus the time this job has already run, $SECONDS).
  if [[ -n "$walltime" ]]; then
    delay=$((walltime - margin - SECONDS))
    if ((delay > 0)); then
      say "wall time ${walltime} s: the study will be stopped in $delay s"
      # (only while this script is still the timer's parent: never a reused PID)
      (
        self=$BASHPID
        sleep "$delay" && [[ "$(ps -o ppid= -p "$self" | tr -d ' ')" == "$$" ]] && kill -USR1 $$
      ) &
      timer_pid=$!
    else
      say "warning: wall time ${walltime} s, minus STOP_MARGIN=${margin} s and $SECONDS s" \
        "already run, leaves no time: no timer, only SIGTERM at the limit stops the study"
    fi
  else
    [[ $mode == local ]] ||
      say "warning: wall time unknown (set WALLTIME): no timer," \
        "only SIGTERM at the limit stops the study"
  fi
  job_start
  if [[ -n "$timer_pid" ]]; then # stop the timer: its sleep first, so it never fires
    {
      pkill -P "$timer_pid"
      kill "$timer_pid"
      wait "$timer_pid"
    } 2>/dev/null
  fi
  job_outcome resubmitted

  # Resubmission: qrerun needs operator rights, so the job submits its script
  # again, run after this job ends (afterany: never two writers on the map),
  # with the settings this job got from its environment and the count.
  local resubmit=(qsub -W "depend=afterany:${PBS_JOBID:-<this job>}") pass=() v entry names new_job
  for v in CONFIG OUTPUT MDRMAP EXTRA_ARGS NP LAUNCHER MAX_REQUEUES STOP_MARGIN WALLTIME \
    JOB_SCRIPT; do
    entry=$(start_env "$v" 2>/dev/null) && pass+=("$entry")
  done
  pass+=("RESUBMIT_COUNT=$((count + 1))")
  names=$(printf '%s,' "${pass[@]%%=*}")
  resubmit+=(-v "${names%,}" "$JOB_SCRIPT")
  if [[ $mode == local ]]; then
    say "not under PBS, so not resubmitted (a job would run: ${pass[*]} ${resubmit[*]});" \
      "to continue, run the same command again: it resumes the map"
    exit 3
  fi
  if [[ " $signals " == *" USR1 "* ]]; then
    : # the warning timer, or qsig -s USR1: resubmit
  elif [[ " $signals " == *" TERM "* || " $signals " == *" INT "* ]] &&
    [[ -n "$walltime" ]] && ((SECONDS < walltime - margin)); then
    # SIGTERM well before the wall time: qdel, not the limit
    say "cancelled (SIGTERM before the wall time): not resubmitted;" \
      "to continue, submit the job again: it resumes the map"
    exit 3
  fi
  if ((count >= MAX_REQUEUES)); then
    say "resubmitted $count times already (MAX_REQUEUES=$MAX_REQUEUES): not resubmitted;" \
      "to continue, submit the job again: it resumes the map"
    exit 3
  fi
  [[ -f "$JOB_SCRIPT" ]] ||
    die 3 "JOB_SCRIPT=$JOB_SCRIPT (relative to $PWD) not found, cannot resubmit;" \
      "submit the job again to continue"
  trap '' USR1 TERM INT # nothing may interrupt the resubmission (SIGKILL still can)
  say "resubmitting: ${pass[*]} ${resubmit[*]}"
  if new_job=$(env "${pass[@]}" "${resubmit[@]}"); then
    say "resubmitted as job $new_job (resubmission $((count + 1)) of at most $MAX_REQUEUES)"
  else
    say "error: qsub failed; to continue, submit the job again"
  fi
  exit 3
}
start_env() { # start_env NAME: NAME=value as this script got it (fails if unset)
  local entry
  while IFS= read -r -d '' entry; do
    [[ "$entry" == "$1="* ]] && printf '%s\n' "$entry" && return 0
  done </proc/$$/environ
  return 1
}

# ---- main -------------------------------------------------------------------
# job_start: the banner and the run (between the scheduler's checks and outcome)
job_start() {
  if ((${#resume[@]})); then say "resuming the map $OUTPUT"; else say "new map $OUTPUT"; fi
  say "running: ${cmd[*]}"
  map_stamp=$(stamp "$OUTPUT")
  job_run
}

study_job_main() { # study_job_main slurm|pbs
  local sched=$1
  mode=local
  if [[ $sched == slurm && -n "${SLURM_JOB_ID:-}" ]]; then mode=slurm; fi
  if [[ $sched == pbs && -n "${PBS_JOBID:-}" ]]; then mode=pbs; fi
  if [[ $sched == pbs && $mode == local && -n "${SLURM_JOB_ID:-}" ]]; then
    say "warning: Slurm job $SLURM_JOB_ID without PBS_JOBID (Slurm's qsub without its" \
      "spank_pbs plugin?): running as on a workstation, nothing will be resubmitted;" \
      "submit jobs/study.sbatch with sbatch instead, or enable spank_pbs"
  fi
  trap 'on_signal USR1' USR1
  trap 'on_signal TERM' TERM
  trap 'on_signal INT' INT
  # A job started with an empty environment (qsub -v under Slurm's PBS
  # wrappers is sbatch --export=none) has no PATH: bash makes one up but does
  # not export it, and mpiexec then finds no ssh or srun to start its daemons.
  export PATH
  # Lustre and GPFS mounts often lack the flock() that HDF5 uses to lock files;
  # opening the map then fails. Only one study writes a map at a time anyway.
  export HDF5_USE_FILE_LOCKING=${HDF5_USE_FILE_LOCKING:-FALSE}
  job_inputs
  job_launcher
  case $sched in
    slurm)
      if [[ $mode == slurm ]]; then
        slurm_main
      fi
      say "$(now) not under Slurm: running on this machine ($(hostname))"
      job_start
      job_outcome requeued
      say "not under Slurm, so not requeued (a job would run 'scontrol requeue \$SLURM_JOB_ID');" \
        "to continue, run the same command again: it resumes the map"
      exit 3
      ;;
    pbs) pbs_main ;;
  esac
}
