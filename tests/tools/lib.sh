# Shared helpers of the tool tests (sourced; W, PYRUN set by the caller).
#   fail MSG        print FAIL: MSG on stderr, exit 1
#   ok MSG          count a passed check and print it
#   py ARGS...      run a Python tool through tools/pyrun
#   run NAME CMD... CMD must exit 0 without a traceback; stdout in $W/NAME.out,
#                   stderr in $W/NAME.err
checks=0

fail() {
  echo "FAIL: $*" >&2
  exit 1
}
ok() {
  checks=$((checks + 1))
  echo "ok $checks: $*"
}
py() { bash "$PYRUN" "$@"; }

run() {
  local name=$1
  shift
  if ! "$@" >"$W/$name.out" 2>"$W/$name.err"; then
    cat "$W/$name.out" "$W/$name.err" >&2
    fail "$name: exited non-zero: $*"
  fi
  if grep -q Traceback "$W/$name.err"; then
    cat "$W/$name.err" >&2
    fail "$name: traceback"
  fi
}
