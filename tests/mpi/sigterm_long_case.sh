#!/usr/bin/env bash
# sigterm_long_case.sh ... NP CONFIG: SIGTERM while every rank is inside a case
# that takes seconds (tests/mpi/long_case.ini) stops the study within seconds
# (exit 3): the case is interrupted, not finished, and stays pending (status 0,
# not failed); --resume then runs it to its end (here: failed, past its work
# budget, with the message). Waits for conditions, not fixed sleeps.
source "$(dirname "$0")/common.sh"
np=$1 config=$2
out="$WORKDIR/sigterm_long_np$np.h5"
log="$WORKDIR/sigterm_long_np$np.log"
rm -f "$out"
"$MPIEXEC" -np "$np" "$MDRMAP" study --quiet --config "$config" --output "$out" 2>"$log" &
pid=$!
ranks() { pgrep -P "$pid" || true; } # the ranks: children of mpirun, by its PID
cpu_seconds() { # CPU seconds the ranks used (utime + stime)
  local total=0 r t
  for r in $(ranks); do
    t=$(awk '{ print $14 + $15 }' "/proc/$r/stat" 2>/dev/null || echo 0)
    total=$((total + t))
  done
  echo $((total / $(getconf CLK_TCK)))
}
# the map exists (created before any case runs), then the ranks have computed
# for a while: every rank is inside its case (each takes seconds of CPU)
for _ in $(seq 1200); do [[ -f "$out" ]] && break; sleep 0.05; done
[[ -f "$out" ]] || fail "the map was not created within 60 s"
for _ in $(seq 1200); do (($(cpu_seconds) >= 2 * np)) && break; sleep 0.05; done
kill -0 "$pid" 2>/dev/null || fail "the study ended before the signal: $(cat "$log")"
signalled=$SECONDS
for r in $(ranks); do kill -TERM "$r"; done # as Slurm signals the tasks
code=0
wait "$pid" || code=$?
took=$((SECONDS - signalled))
cat "$log" >&2
[[ $code == 3 ]] || fail "exit code $code after SIGTERM, expected 3"
((took <= 30)) || fail "the study took $took s to stop after SIGTERM (at most 30 s)"
grep -q -- "--resume" "$log" || fail "no resume hint in the message"
"${CHECK[@]}" --quiet "$out"
cat >"$WORKDIR/status.py" <<'PY'
# pyrun-needs: h5py numpy
import sys, h5py
with h5py.File(sys.argv[1], "r") as f:
    print(" ".join(str(int(s)) for s in f["/results/status"][()]))
PY
status=$("$PYRUN" "$WORKDIR/status.py" "$out")
[[ $status == "0 0" ]] || fail "status after SIGTERM: $status, expected both cases pending (0 0)"
study "$np" --config "$config" --output "$out" --resume
"${CHECK[@]}" --complete --expect-failed 2 "$out"
echo "PASS: SIGTERM inside long cases at np=$np: exit 3 after $took s, cases pending, resumed"
