#!/usr/bin/env bash
# quiet_error.sh ...: under Open MPI's mpirun, a bad input to mdrmap study
# (exit 2) is one line from rank 0, first in the output; mpirun adds a banner
# of about ten lines after it, which `mpirun -q` leaves out. With -q an
# option's error (before MPI starts) and a config's (after) are exactly their
# one line, exit 2; `mdrmap study --help` names `mpirun -q` (issue 32).
# Skipped (77) where the launcher is not Open MPI's.
source "$(dirname "$0")/common.sh"
dir="$WORKDIR/quiet_error"
rm -rf "$dir"
mkdir -p "$dir"
"$MDRMAP" study --help >"$dir/help.txt"
grep -q "'mpirun -q'" "$dir/help.txt" || fail "mdrmap study --help does not name 'mpirun -q'"
version=$("$MPIEXEC" --version 2>&1 || true)
[[ $version == *"Open MPI"* || $version == *"OpenRTE"* ]] || {
  echo "SKIP: $MPIEXEC is not Open MPI's mpirun (-q is Open MPI's)"
  exit 77
}
printf '[grid]\nd = 1e-3\nR = 1\ntau = 0\nG33 = 1\nv = 1\n' >"$dir/g33.ini"
check() { # check NAME EXPECTED-START ARGS...: exit 2, stderr exactly one line
  local name=$1 want=$2 code=0
  shift 2
  "$MPIEXEC" -q -np 2 "$MDRMAP" study "$@" >"$dir/$name.out" 2>"$dir/$name.err" || code=$?
  [[ $code == 2 ]] || fail "$name: exit $code, expected 2: $(cat "$dir/$name.err")"
  [[ ! -s "$dir/$name.out" ]] || fail "$name: output on stdout: $(cat "$dir/$name.out")"
  (($(wc -l <"$dir/$name.err") == 1)) || fail "$name: not one line: $(cat "$dir/$name.err")"
  [[ $(cat "$dir/$name.err") == "$want"* ]] || fail "$name: $(cat "$dir/$name.err")"
  echo "$name: $(cat "$dir/$name.err")"
}
check option "mdrmap study: error: --bogus: " --config "$dir/g33.ini" --output "$dir/x.h5" --bogus
check config "mdrmap study: error: grid.G33: " --config "$dir/g33.ini" --output "$dir/x.h5"
[[ ! -e "$dir/x.h5" ]] || fail "a refused study created its map"
echo "PASS: mpirun -q: a bad input is its one line, exit 2; --help says so"
