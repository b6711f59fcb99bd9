#!/usr/bin/env bash
# concurrent.sh ... QUICK QUICK_REF LONG LONG_REF: two jobs on one map (issue 23,
# class 5). QUICK and LONG are study configs (a fraction of a second, a few
# seconds), *_REF their maps made at np = 1.
# The jobs are MPI singletons (mdrmap run without mpirun), so that $! is the
# PID of the job's rank 0, the holder of the map's lock.
#
#  1. Two `mdrmap study --output m.h5` started together, 10 times: one exits
#     0, the other is refused (exit 2, one line naming --output), and the map
#     is the first job's complete map, equal to QUICK_REF (never mixed with
#     the second's, never replaced); no temporary file is left.
#  2. `--overwrite` of a map a running study is writing (the study is
#     stopped, SIGSTOP, once its map exists, so that it is surely running):
#     refused, exit 2, one line naming --output and the running job's PID;
#     the running job (LONG), continued, exits 0 and its map equals LONG_REF.
#  3. The same with `--resume`: refused (exit 2, naming --resume and the PID).
source "$(dirname "$0")/common.sh"
quick=$1 quick_ref=$2 long=$3 long_ref=$4
[[ -f "$quick_ref" && -f "$long_ref" ]] || fail "no reference maps $quick_ref $long_ref"
dir="$WORKDIR/concurrent"
rm -rf "$dir"
mkdir -p "$dir"
cd "$dir" || exit 1

job() { # job CONFIG OUT ERR [args]: a study as an MPI singleton, in the background
  local config=$1 out=$2 err=$3
  shift 3
  "$MDRMAP" study --quiet --config "$config" --output "$out" "$@" 2>"$err" &
}
refused() { # refused WHAT ERR CODE WORD...: exit 2, one mdrmap line with each word (ERE)
  local what=$1 err=$2 code=$3 line
  shift 3
  line=$(grep '^mdrmap' "$err" || true)
  [[ $code == 2 ]] || fail "$what: exit $code (expected 2): $(cat "$err")"
  [[ $(printf '%s\n' "$line" | grep -c .) == 1 ]] || fail "$what: not one line: $(cat "$err")"
  for w in "$@"; do
    grep -qE -- "$w" <<<"$line" || fail "$what: message lacks '$w': $line"
  done
  printf '%s\n' "$line"
}
wait_for_file() { # wait_for_file PATH PID: until PATH exists (PID must still run), 120 s at most
  for _ in $(seq 1200); do
    [[ -e $1 ]] && return 0
    kill -0 "$2" 2>/dev/null || fail "the job ended before its map $1 appeared"
    sleep 0.1
  done
  fail "no map $1 after 120 s"
}

# -- 1. two studies started together --------------------------------------------------
for try in $(seq 10); do
  out="$dir/together.h5"
  rm -f "$out"*
  job "$quick" "$out" "$dir/a.err"
  a=$!
  job "$quick" "$out" "$dir/b.err"
  b=$!
  ca=0 cb=0
  wait "$a" || ca=$?
  wait "$b" || cb=$?
  if [[ $ca == 0 && $cb == 2 ]]; then
    line=$(refused "try $try, second job" "$dir/b.err" "$cb" --output)
  elif [[ $ca == 2 && $cb == 0 ]]; then
    line=$(refused "try $try, first job" "$dir/a.err" "$ca" --output)
  else
    fail "try $try: exits $ca and $cb (expected 0 and 2): $(cat "$dir/a.err" "$dir/b.err")"
  fi
  "${CHECK[@]}" --quiet --complete "$out" || fail "try $try: the map is not complete"
  "${COMPARE[@]}" "$out" "$quick_ref" >/dev/null || fail "try $try: the map differs from the reference"
  compgen -G "$out.tmp-*" >/dev/null && fail "try $try: temporary files left: $(ls "$dir")"
  echo "try $try: exits $ca, $cb; map complete, equal to the reference; $line"
done

# -- 2. and 3. --overwrite and --resume of a map in use ---------------------------------
for opt in --overwrite --resume; do
  out="$dir/busy${opt#--}.h5"
  rm -f "$out"
  job "$long" "$out" "$dir/first.err"
  first=$!
  wait_for_file "$out" "$first"
  kill -STOP "$first"
  code=0
  "$MDRMAP" study --quiet --config "$long" --output "$out" "$opt" 2>"$dir/second.err" || code=$?
  kill -CONT "$first"
  word="--output"
  [[ $opt == --resume ]] && word="--resume"
  line=$(refused "$opt of a map in use" "$dir/second.err" "$code" "$word" "process $first\\b")
  first_code=0
  wait "$first" || first_code=$?
  [[ $first_code == 0 ]] || fail "$opt: the running job failed ($first_code): $(cat "$dir/first.err")"
  "${COMPARE[@]}" "$out" "$long_ref" >/dev/null ||
    fail "$opt: the running job's map differs from the reference"
  echo "$opt of a map in use: $line"
  echo "  the running job completed its map, equal to the reference"
done
echo "PASS: concurrent studies on one map"
