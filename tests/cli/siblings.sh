#!/usr/bin/env bash
# mdrmap runs study and fit as the programs beside it (mdrmap-study,
# mdrmap-fit), and links none of what they need:
#   bash tests/cli/siblings.sh MDRMAP
# - MDRMAP links neither MPI, HDF5 nor Ceres (ldd);
# - MDRMAP study --help and fit --help print their usage (from the siblings);
# - a copy of MDRMAP alone in a directory: study and fit each exit 1 with one
#   line naming the missing program, nothing on stdout.
set -euo pipefail
MDRMAP=${1:?usage: siblings.sh MDRMAP}
fail() { echo "FAIL: $*" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

heavy=$(ldd "$MDRMAP" | grep -E 'lib(mpi|hdf5|ceres)' || true)
[[ -z "$heavy" ]] || fail "$MDRMAP links $heavy"

for cmd in study fit; do
  "$MDRMAP" "$cmd" --help >"$work/out" 2>"$work/err" || fail "$cmd --help: exit $?: $(cat "$work/err")"
  grep -q "^Usage: .*mdrmap $cmd" "$work/out" || fail "$cmd --help: no usage: $(head -n 2 "$work/out")"
done

mkdir "$work/alone"
cp "$MDRMAP" "$work/alone/mdrmap"
for cmd in study fit; do
  code=0
  "$work/alone/mdrmap" "$cmd" --help >"$work/out" 2>"$work/err" || code=$?
  [[ $code == 1 ]] || fail "$cmd without its program: exit $code, not 1"
  [[ ! -s "$work/out" ]] || fail "$cmd without its program wrote to stdout"
  [[ $(wc -l <"$work/err") == 1 ]] || fail "$cmd without its program: not one line: $(cat "$work/err")"
  grep -q "^mdrmap: error: cannot run $work/alone/mdrmap-$cmd: " "$work/err" ||
    fail "$cmd without its program: $(cat "$work/err")"
done
echo "PASS: study and fit run beside mdrmap, which links none of MPI, HDF5, Ceres"
