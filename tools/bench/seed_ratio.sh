#!/usr/bin/env bash
# CPU of the seed's own workload against the build before velocity histories
# (issue 22): the 1e5-case one-step grid tools/bench/seed_grid_1e5.ini (61
# samples, np = 1), run by this checkout's mdrmap and by commit 8876e42 side
# by side, in alternating pairs:
#
#   bash tools/bench/seed_ratio.sh [MDRMAP] [PAIRS]
#
# Builds 8876e42 in a scratch directory ($SCRATCH, default a temporary
# directory removed at exit; `git archive 8876e42 | tar -x`, Release, the
# mdrmap target only; nothing is written to the checkout), then runs PAIRS
# (default 5) alternating pairs and prints each run's CPU seconds (user +
# system of mpirun and its children, /usr/bin/time), the medians and their
# ratio (this build / 8876e42; the target is <= 1.00). MDRMAP defaults to
# build/src/mdrmap (a Release build). Each map must hold 1e5 done cases.
# As root it sets Open MPI's OMPI_ALLOW_RUN_AS_ROOT for itself.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
MDRMAP=${1:-$ROOT/build/src/mdrmap}
PAIRS=${2:-5}
OLD_COMMIT=8876e42
CONFIG=$ROOT/tools/bench/seed_grid_1e5.ini
log() { printf 'seed_ratio: %s\n' "$*" >&2; }
[[ -x "$MDRMAP" ]] || { log "no executable $MDRMAP"; exit 2; }
[[ "$PAIRS" =~ ^[1-9][0-9]*$ ]] || { log "PAIRS must be a positive integer, got '$PAIRS'"; exit 2; }
[[ -x /usr/bin/time ]] || { log "needs /usr/bin/time (apt-get install time)"; exit 2; }
if [[ "$(id -u)" == 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
SCRATCH=${SCRATCH:-$work/old}

# the old build, outside the checkout
OLD=$SCRATCH/build/src/mdrmap
if [[ ! -x "$OLD" ]]; then
  log "building $OLD_COMMIT in $SCRATCH"
  mkdir -p "$SCRATCH"
  git -C "$ROOT" archive "$OLD_COMMIT" | tar -x -C "$SCRATCH"
  if ! cmake -S "$SCRATCH" -B "$SCRATCH/build" -DCMAKE_BUILD_TYPE=Release \
    -DMDRMAP_BUILD_TESTS=OFF >"$work/build.log" 2>&1 ||
    ! cmake --build "$SCRATCH/build" --parallel "${JOBS:-2}" --target mdrmap >>"$work/build.log" 2>&1; then
    cat "$work/build.log" >&2
    exit 1
  fi
fi

median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
# CPU seconds of one study run; checks that every case is done
cpu_of() {
  local exe=$1 out=$work/map.h5
  rm -f "$out"
  /usr/bin/time -f '%U %S' -o "$work/time" mpirun -np 1 "$exe" study --config "$CONFIG" \
    --output "$out" >"$work/log" 2>&1 || { cat "$work/log" >&2; exit 1; }
  grep -q '100000 done, 0 failed' "$work/log" || { cat "$work/log" >&2; log "not all cases done"; exit 1; }
  awk '{printf "%.2f", $1 + $2}' "$work/time"
}
declare -a old new
printf '%-5s %10s %10s %7s\n' pair "$OLD_COMMIT" this ratio
for ((p = 1; p <= PAIRS; p++)); do
  o=$(cpu_of "$OLD")
  n=$(cpu_of "$MDRMAP")
  old+=("$o") new+=("$n")
  printf '%-5s %8s s %8s s %7.3f\n' "$p" "$o" "$n" "$(awk -v a="$n" -v b="$o" 'BEGIN {print a / b}')"
done
mo=$(printf '%s\n' "${old[@]}" | median)
mn=$(printf '%s\n' "${new[@]}" | median)
echo
printf 'median CPU: %s %.2f s, this build %.2f s, ratio %.3f (target <= 1.00; load average %s)\n' \
  "$OLD_COMMIT" "$mo" "$mn" "$(awk -v a="$mn" -v b="$mo" 'BEGIN {print a / b}')" \
  "$(cut -d' ' -f1-3 /proc/loadavg)"
