#!/usr/bin/env bash
# Speed-up of `mdrmap study` from P = 1 to P = 2 ranks, end to end (mpirun
# start-up, preflight, map creation, dispatch, close), on the load-controlled
# slide-hold-slide study tools/bench/shs_1e4.ini (10000 cases):
#
#   bash tools/bench/study_speedup.sh [MDRMAP] [REPEATS]
#
# Runs P = 1 and P = 2 alternately REPEATS times (default 3), prints each run's
# end-to-end and dispatch wall time and the medians, and the ratio of the
# medians. MDRMAP defaults to build/src/mdrmap. Run it on an otherwise idle
# machine. As root it sets Open MPI's OMPI_ALLOW_RUN_AS_ROOT for itself.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
MDRMAP=${1:-$ROOT/build/src/mdrmap}
REPEATS=${2:-3}
CONFIG=$ROOT/tools/bench/shs_1e4.ini
[[ -x "$MDRMAP" ]] || { echo "study_speedup: no executable $MDRMAP" >&2; exit 2; }
[[ "$REPEATS" =~ ^[1-9][0-9]*$ ]] || { echo "study_speedup: REPEATS must be a positive integer, got '$REPEATS'" >&2; exit 2; }
if [[ "$(id -u)" == 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
declare -A e2e dispatch
printf '%-4s %-3s %12s %12s\n' run P "end to end" dispatch
for ((r = 1; r <= REPEATS; r++)); do
  for np in 1 2; do
    out="$work/shs_np$np.h5"
    rm -f "$out"
    t0=$(date +%s.%N)
    mpirun -np "$np" "$MDRMAP" study --quiet --config "$CONFIG" --output "$out" >"$work/log" 2>&1 ||
      { cat "$work/log" >&2; exit 1; }
    t1=$(date +%s.%N)
    wall=$(awk -v a="$t0" -v b="$t1" 'BEGIN {printf "%.3f", b - a}')
    disp=$(sed -n 's/.*wall \([0-9.]*\) s.*/\1/p' "$work/log" | head -1)
    e2e[$np]+="$wall "
    dispatch[$np]+="$disp "
    printf '%-4s %-3s %10s s %10s s\n' "$r" "$np" "$wall" "$disp"
  done
done
m1=$(tr ' ' '\n' <<<"${e2e[1]}" | grep . | median)
m2=$(tr ' ' '\n' <<<"${e2e[2]}" | grep . | median)
d1=$(tr ' ' '\n' <<<"${dispatch[1]}" | grep . | median)
d2=$(tr ' ' '\n' <<<"${dispatch[2]}" | grep . | median)
echo
printf 'median end to end: P = 1 %.2f s, P = 2 %.2f s, speed-up %.2fx\n' "$m1" "$m2" "$(awk -v a="$m1" -v b="$m2" 'BEGIN {print a / b}')"
printf 'median dispatch:   P = 1 %.2f s, P = 2 %.2f s, speed-up %.2fx\n' "$d1" "$d2" "$(awk -v a="$d1" -v b="$d2" 'BEGIN {print a / b}')"
