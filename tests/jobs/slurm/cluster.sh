#!/usr/bin/env bash
# cluster.sh: a one-node Slurm cluster for the tests, started by hand (no
# systemd): its own munged, slurmctld and slurmd, its own ports, config, state
# and logs, all under one directory; root only.
#
#   cluster.sh start DIR [MPI_DEFAULT] [PLUGSTACK_LINE]
#       writes DIR/slurm.conf (MpiDefault=MPI_DEFAULT, default none; the
#       optional plugstack line, e.g. "optional /path/spank_pbs.so"), starts the
#       daemons and waits (at most 60 s) until the node is idle. Clients need
#       SLURM_CONF=DIR/slurm.conf (DIR/env sets it). Exit 77 with the reason
#       when the packages are missing or a daemon does not start (a skip).
#   cluster.sh stop DIR
#       stops the daemons by the PIDs recorded in DIR (SIGTERM, then SIGKILL
#       after 15 s) and every job step they left. Always safe to call.
#
# Settings that keep the tests fast: AuthInfo cred_expire=10 (a requeued job
# waits cred_expire + 1 s before it runs again; 121 s by default), scheduling
# every second, KillWait=5, MinJobAge=600 (finished jobs stay visible to
# scontrol). ProctrackType=proctrack/linuxproc, TaskPlugin=task/none: no cgroups.
set -euo pipefail

usage() {
  echo "usage: $0 start DIR [MPI_DEFAULT] [PLUGSTACK_LINE] | stop DIR" >&2
  exit 2
}
(($# >= 2)) || usage
action=$1
DIR=$2
skip() {
  echo "SKIP: $*" >&2
  exit 77
}
log() { echo "cluster: $*" >&2; }

# ---- stop -----------------------------------------------------------------
# alive PID NAME: PID runs a program called NAME (never a reused PID; a
# zombie that init has not reaped yet is dead)
alive() {
  local stat comm
  read -r stat comm < <(ps -o stat=,comm= -p "$1" 2>/dev/null) || return 1
  [[ $comm == "$2" && $stat != Z* ]]
}
stop_one() { # stop_one PIDFILE NAME
  local pid i
  [[ -s "$1" ]] || return 0
  pid=$(cat "$1")
  if alive "$pid" "$2"; then
    kill -TERM "$pid" 2>/dev/null || true
    for ((i = 0; i < 150; i++)); do
      alive "$pid" "$2" || break
      sleep 0.1
    done
    if alive "$pid" "$2"; then
      log "$2 (PID $pid) still running 15 s after SIGTERM: SIGKILL"
      kill -KILL "$pid" 2>/dev/null || true
    fi
  fi
  rm -f "$1"
}
if [[ $action == stop ]]; then
  [[ -d "$DIR" ]] || exit 0
  # job steps outlive slurmd (slurmstepd): end every process whose environment
  # names this cluster's config, by PID
  if [[ -s "$DIR/slurm.conf" ]]; then
    while read -r pid comm; do
      case $comm in
        slurmstepd | mdrmap | srun | mpirun | mpiexec | orterun | orted | bash | sleep)
          [[ $pid != "$$" ]] &&
            grep -qzxF "SLURM_CONF=$DIR/slurm.conf" "/proc/$pid/environ" 2>/dev/null &&
            kill -KILL "$pid" 2>/dev/null
          ;;
      esac
    done < <(ps -eo pid=,comm=)
  fi
  stop_one "$DIR/slurmd.pid" slurmd
  stop_one "$DIR/slurmctld.pid" slurmctld
  stop_one "$DIR/munged.pid" munged
  exit 0
fi
[[ $action == start ]] || usage
MPI_DEFAULT=${3:-none}
PLUGSTACK_LINE=${4:-}

# ---- start ----------------------------------------------------------------
[[ "$(id -u)" == 0 ]] || skip "the one-node Slurm cluster needs root (slurmd runs jobs as their users)"
for prog in munged slurmctld slurmd sbatch scontrol sinfo; do
  command -v "$prog" >/dev/null 2>&1 ||
    skip "$prog not installed: the Slurm packages come with 'MDRMAP_SLURM=1 bash tools/setup.sh' (CI installs them)"
done
mkdir -p "$DIR"
DIR=$(cd "$DIR" && pwd)
# munged refuses a socket path that is not short enough, or directories that
# others can write
((${#DIR} < 80)) || skip "cluster directory path too long for the munge socket: $DIR"
mkdir -p "$DIR/munge" "$DIR/state" "$DIR/spool" "$DIR/tmp"
chmod 1777 "$DIR/tmp"
# users reach munged's socket; its key file is root's alone
chmod 700 "$DIR/state"
chmod 755 "$DIR" "$DIR/spool" "$DIR/munge"

# free TCP ports for slurmctld and slurmd (several clusters may run at once)
port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }
pick_port() {
  local p i
  for ((i = 0; i < 200; i++)); do
    p=$((20000 + RANDOM % 20000))
    port_free "$p" && port_free "$((p + 1))" && echo "$p" && return 0
  done
  return 1
}
port=$(pick_port) || skip "no free TCP port pair for slurmctld and slurmd"

node=$(hostname -s)
cpus=$(slurmd -C 2>/dev/null | sed -n 's/.* CPUs=\([0-9]*\).*/\1/p' | head -n 1)
[[ -n "$cpus" ]] || cpus=$(nproc)
plugstack=$DIR/plugstack.conf
printf '%s\n' "$PLUGSTACK_LINE" >"$plugstack"
cat >"$DIR/slurm.conf" <<CONF
# written by tests/jobs/slurm/cluster.sh
ClusterName=mdrmaptest
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$DIR/munge/munge.sock,cred_expire=10
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
# the PMIx plugin's directories (named by job and step IDs) go under TmpFS, and
# job IDs start at the port: several clusters at once never share a name
TmpFS=$DIR/tmp
FirstJobId=$port
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/slurmctld.log
SlurmdLogFile=$DIR/slurmd.log
SlurmctldDebug=debug2
SlurmdDebug=info
PlugStackConfig=$plugstack
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SwitchType=switch/none
MpiDefault=$MPI_DEFAULT
SchedulerType=sched/builtin
SchedulerParameters=sched_interval=1,sched_min_interval=100000
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
JobRequeue=1
KillWait=5
MinJobAge=600
InactiveLimit=0
MessageTimeout=10
SlurmdTimeout=300
SlurmctldTimeout=300
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=debug Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$DIR/slurm.conf
echo "export SLURM_CONF=$DIR/slurm.conf" >"$DIR/env"

fail_start() { # fail_start WHAT LOG: stop what runs, show the log, skip
  log "$1; the end of $2:"
  tail -n 20 "$2" >&2 || true
  "$0" stop "$DIR" || true
  skip "$1"
}

# munged: its own key and socket (never the system's munged, never its key)
[[ -s "$DIR/munge/munge.key" ]] || {
  dd if=/dev/urandom of="$DIR/munge/munge.key" bs=1024 count=1 status=none
  chmod 400 "$DIR/munge/munge.key"
}
munged --force --key-file="$DIR/munge/munge.key" --socket="$DIR/munge/munge.sock" \
  --pid-file="$DIR/munged.pid" --log-file="$DIR/munged.log" \
  --seed-file="$DIR/munge/munged.seed" >>"$DIR/munged.log" 2>&1 ||
  fail_start "munged did not start" "$DIR/munged.log"

slurmctld -f "$DIR/slurm.conf" -i >>"$DIR/slurmctld.log" 2>&1 ||
  fail_start "slurmctld did not start" "$DIR/slurmctld.log"
slurmd -f "$DIR/slurm.conf" >>"$DIR/slurmd.log" 2>&1 ||
  fail_start "slurmd did not start" "$DIR/slurmd.log"

# wait (at most 60 s) for the node to be idle
state=""
for ((i = 0; i < 600; i++)); do
  state=$(sinfo -h -n "$node" -o %T 2>/dev/null | head -n 1) || state=""
  [[ $state == idle ]] && break
  sleep 0.1
done
[[ $state == idle ]] || fail_start "the node is not idle 60 s after the start (state '${state:-none}')" \
  "$DIR/slurmctld.log"
log "one-node Slurm up in $DIR: node $node, $cpus CPUs, ports $port/$((port + 1)), MpiDefault=$MPI_DEFAULT"
