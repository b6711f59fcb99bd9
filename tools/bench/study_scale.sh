#!/usr/bin/env bash
# Memory and map cost of `mdrmap study` at scale (issue 12), P = 2:
#
#   bash tools/bench/study_scale.sh [MDRMAP] [DIR]
#
#   1. a 1e7-case one-step grid (d 100 x R 100 x tau 100 x v 10, exact
#      solver, 3 samples) run to the end: each rank's peak RSS (mdrmap study
#      prints it), the wall time, the map's bytes per case and the bytes the
#      run wrote (/usr/bin/time's file system outputs);
#   2. a 1e8-case grid (v 100): started, 30 s of dispatch after the map
#      exists, then SIGTERM to the ranks (by PID): each rank's peak RSS
#      (VmHWM), the time to the map, the cases done, the map's size.
# Needs about 48 GB free in DIR (default: a new directory under /tmp); the
# maps are deleted at the end. MDRMAP defaults to build/src/mdrmap. As root it
# sets Open MPI's OMPI_ALLOW_RUN_AS_ROOT for itself.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
MDRMAP=${1:-$ROOT/build/src/mdrmap}
DIR=${2:-$(mktemp -d)}
[[ -x "$MDRMAP" ]] || { echo "study_scale: no executable $MDRMAP" >&2; exit 2; }
mkdir -p "$DIR"
if [[ "$(id -u)" == 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
trap 'rm -f "$DIR"/g7.h5 "$DIR"/g8.h5 "$DIR"/*.tmp-*' EXIT
grid() { # grid N_V: 100 x 100 x 100 x N_V one-step cases
  printf '[grid]\nd = logspace:1e-4:1e-2:100\nR = linspace:1:2:100\ntau = linspace:0.5:2:100\n'
  printf 'v = logspace:0.1:10:%s\nv1_over_v = 0.1\n[run]\nsamples = 3\n' "$1"
}
grid 10 >"$DIR/g7.ini"
grid 100 >"$DIR/g8.ini"

echo "== 1e7 cases, run to the end"
/usr/bin/time -f "end to end %e s, file system outputs %O blocks of 512 bytes" \
  mpirun -np 2 "$MDRMAP" study --quiet --config "$DIR/g7.ini" --output "$DIR/g7.h5" 2>&1 | tail -3
bytes=$(stat -c %s "$DIR/g7.h5")
echo "map: $bytes bytes, $(awk -v b="$bytes" 'BEGIN {printf "%.1f", b / 1e7}') bytes per case"
rm -f "$DIR/g7.h5"

echo "== 1e8 cases, started"
start=$(date +%s)
mpirun -np 2 "$MDRMAP" study --quiet --config "$DIR/g8.ini" --output "$DIR/g8.h5" >"$DIR/g8.log" 2>&1 &
pid=$!
ranks=""
for _ in $(seq 1 100); do
  ranks=$(pgrep -P "$pid" -d ' ' || true)
  [[ -n "$ranks" ]] && break
  sleep 0.2
done
[[ -n "$ranks" ]] || { echo "study_scale: no ranks under mpirun $pid" >&2; exit 1; }
while [[ ! -f "$DIR/g8.h5" ]] && kill -0 "$pid" 2>/dev/null; do sleep 1; done
[[ -f "$DIR/g8.h5" ]] || { cat "$DIR/g8.log" >&2; exit 1; }
echo "map created after $(($(date +%s) - start)) s: $(stat -c %s "$DIR/g8.h5") bytes"
sleep 30
for r in $ranks; do echo "rank pid $r: $(grep VmHWM /proc/"$r"/status)"; done
kill -TERM $ranks
wait "$pid" || true
grep -E "interrupted|peak memory" "$DIR/g8.log"
