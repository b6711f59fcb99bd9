#!/usr/bin/env bash
# rss_scale.sh ...: a rank's memory does not grow with the number of cases.
# Runs the same grid study at 1e4 and 1e6 cases on 2 ranks, and reads each
# rank's peak resident memory (VmHWM in /proc/PID/status) twice: when the map
# exists (the peak of the checks and the map's creation), then, after
# resetting it there (/proc/PID/clear_refs), once the map shows cases done
# (the peak of the dispatch; the ranks are stopped to read it). The dispatch
# peak may grow by at most 16 MiB from the smaller study to the larger (rank
# 0 holds 1 byte of status per case: ~1 MiB), and so may the creation peak
# (io::MapFile::create takes the cases by range).
# Needs ~600 MB of disk for the larger map (skipped, exit 77, without).
source "$(dirname "$0")/common.sh"
np=2
small=10000 large=1000000
bound_mib=16
create_bytes_rank0=0 create_bytes_other=0 # (MapFile::create takes the cases by range)

free_kib=$(df --output=avail -k "$WORKDIR" | tail -1 | tr -d ' ')
if ((free_kib < 1500000)); then
  echo "SKIP: $WORKDIR has $free_kib KiB free, the 1e6-case map needs ~600 MB"
  exit 77
fi

poll="$WORKDIR/rss_poll.py"
cat >"$poll" <<'PY'
# pyrun-needs: h5py numpy
"""poll.py MAP MIN_DONE TIMEOUT PID...: waits until MIN_DONE cases of MAP are
done (or failed), then stops the PIDs (SIGSTOP) so that their memory can be
read; exit 1 on timeout or when the PIDs are gone."""
import os, signal, sys, time
import h5py
path, need, timeout = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
pids = [int(p) for p in sys.argv[4:]]
end = time.monotonic() + timeout
while time.monotonic() < end:
    try:
        with h5py.File(path, "r", locking=False) as f:
            done = int((f["results/status"][...] != 0).sum())
    except OSError:
        done = 0
    if done >= need:
        for p in pids:
            os.kill(p, signal.SIGSTOP)
        print(done)
        sys.exit(0)
    if not all(os.path.exists(f"/proc/{p}") for p in pids):
        sys.exit(1)
    time.sleep(0.02)
sys.exit(1)
PY

grid() { # grid N_D N_TAU: N_D * N_TAU * 100 cases of the element row (~1.8 ms each)
  printf '[grid]\nd = logspace:1e-4:1e-2:%s\nR = 1\ntau = linspace:0.5:2:%s\n' "$1" "$2"
  printf 'v = logspace:1e-3:1e3:10\nv1_over_v = logspace:1e-4:0.9:10\n'
  printf '[run]\nsamples = 101\nsolver = row\nrtol = 1e-3\n'
}

declare -A peak create
measure() { # measure N_CASES N_D N_TAU: sets create[N,i] and peak[N,i] (KiB) of rank pid i
  local n=$1 ini="$WORKDIR/rss_$1.ini" out="$WORKDIR/rss_$1.h5" log="$WORKDIR/rss_$1.log"
  grid "$2" "$3" >"$ini"
  rm -f "$out"
  "$MPIEXEC" -np "$np" "$MDRMAP" study --quiet --config "$ini" --output "$out" 2>"$log" &
  local pid=$! t
  for ((t = 0; t < 2400; ++t)); do # the map is created in full before dispatch: up to 120 s
    [[ -f "$out" ]] && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.05
  done
  [[ -f "$out" ]] || fail "$n cases: no map after 120 s: $(cat "$log")"
  local ranks
  mapfile -t ranks < <(pgrep -P "$pid")
  [[ ${#ranks[@]} == "$np" ]] || fail "$n cases: found ${#ranks[@]} ranks under mpirun $pid"
  local i=0
  for r in "${ranks[@]}"; do
    create[$n,$i]=$(awk '/^VmHWM:/ {print $2}' "/proc/$r/status")
    echo 5 >"/proc/$r/clear_refs" || fail "cannot reset the peak RSS of $r (Linux >= 4.0)"
    i=$((i + 1))
  done
  "$PYRUN" "$poll" "$out" 500 120 "${ranks[@]}" >/dev/null ||
    fail "$n cases: dispatch did not get under way: $(cat "$log")"
  i=0
  for r in "${ranks[@]}"; do
    peak[$n,$i]=$(awk '/^VmHWM:/ {print $2}' "/proc/$r/status")
    i=$((i + 1))
  done
  kill -TERM "${ranks[@]}"
  kill -CONT "${ranks[@]}"
  local code=0
  wait "$pid" || code=$?
  [[ $code == 3 ]] || fail "$n cases: exit $code after SIGTERM, expected 3: $(cat "$log")"
  grep -q 'peak memory (max RSS): rank 0 .* MiB, rank 1 .* MiB' "$log" ||
    fail "$n cases: no peak memory in the summary: $(cat "$log")"
  rm -f "$out"
}

measure "$small" 10 10
measure "$large" 100 100
mib() { awk -v k="$1" 'BEGIN {printf "%.1f", k / 1024}'; }
sorted() { printf '%s\n' "$@" | sort -n | tr '\n' ' '; }
status=0
check() { # check WHAT SMALL_KIB LARGE_KIB ALLOWED_KIB
  local grew=$(($3 - $2))
  if ((grew > $4)); then
    echo "FAIL: $1 grew by $(mib $grew) MiB from $small to $large cases, allowed $(mib "$4")" >&2
    status=1
  fi
}
# the ranks' pids come in no particular order: compare the smaller peaks and the larger
read -r -a ds <<<"$(sorted "${peak[$small,0]}" "${peak[$small,1]}")"
read -r -a dl <<<"$(sorted "${peak[$large,0]}" "${peak[$large,1]}")"
read -r -a cs <<<"$(sorted "${create[$small,0]}" "${create[$small,1]}")"
read -r -a cl <<<"$(sorted "${create[$large,0]}" "${create[$large,1]}")"
echo "dispatch peak RSS of the 2 ranks: $small cases $(mib "${ds[0]}"), $(mib "${ds[1]}") MiB;" \
  "$large cases $(mib "${dl[0]}"), $(mib "${dl[1]}") MiB"
echo "checks and creation peak RSS: $small cases $(mib "${cs[0]}"), $(mib "${cs[1]}") MiB;" \
  "$large cases $(mib "${cl[0]}"), $(mib "${cl[1]}") MiB"
check "the smaller dispatch peak" "${ds[0]}" "${dl[0]}" $((bound_mib * 1024))
check "the larger dispatch peak" "${ds[1]}" "${dl[1]}" $((bound_mib * 1024))
extra=$((large - small))
check "the smaller creation peak" "${cs[0]}" "${cl[0]}" $((bound_mib * 1024 + extra * create_bytes_other / 1024))
check "the larger creation peak" "${cs[1]}" "${cl[1]}" $((bound_mib * 1024 + extra * create_bytes_rank0 / 1024))
((status == 0)) || exit 1
echo "PASS: the dispatch's peak RSS per rank grows by less than $bound_mib MiB from $small to $large cases"
