#!/usr/bin/env bash
# tmp_files.sh MDRMAP WORKDIR: `mdrmap simulate --output FILE` writes to
# FILE.tmp.PID and renames it into place at the end; ended by SIGINT, SIGTERM
# or SIGHUP while it computes, it removes the temporary (issue 32: a 0-byte
# FILE.tmp.PID was left behind) and FILE is not created; the process ends by
# that signal. Waits for conditions (the temporary exists), not fixed sleeps.
set -euo pipefail
MDRMAP=$1 WORKDIR=$2
mkdir -p "$WORKDIR"
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
# a case the row cannot finish (a Maxwell branch 1e12 times stiffer than the
# foundation, under load): it works for seconds (about 13 s of CPU, until its
# work budget ends), long enough to be signalled while computing
long_case=(simulate --F0 0.05 --R 10 --tau 0 --G 1 --prony 1e12:1 --v 1 --v1 0.1 --solver row
  --rtol 1e-3 --samples 21)
# job control: a background command of a script otherwise starts with SIGINT
# ignored (and an ignored SIGINT stays ignored, as under nohup)
set -m
for sig in INT TERM HUP; do
  out="$WORKDIR/signal_$sig.csv"
  rm -f "$out" "$out".tmp.*
  "$MDRMAP" "${long_case[@]}" --output "$out" 2>"$WORKDIR/signal_$sig.log" &
  pid=$!
  tmp="$out.tmp.$pid"
  for _ in $(seq 1200); do [[ -e $tmp ]] && break; sleep 0.05; done
  [[ -e $tmp ]] || fail "SIG$sig: $tmp was not created within 60 s"
  kill -0 "$pid" 2>/dev/null || fail "SIG$sig: the run ended before the signal"
  kill -s "$sig" "$pid"
  code=0
  wait "$pid" || code=$?
  want=$((128 + $(kill -l "$sig")))
  [[ $code == "$want" ]] || fail "SIG$sig: exit status $code, expected $want (ended by the signal)"
  left=$(find "$WORKDIR" -maxdepth 1 -name "signal_$sig.csv*")
  [[ -z $left ]] || fail "SIG$sig: left behind: $left"
  echo "SIG$sig: ended by the signal, no temporary left"
done
echo "PASS: no temporary file left on SIGINT, SIGTERM, SIGHUP"
