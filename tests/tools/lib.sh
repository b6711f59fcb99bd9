# shellcheck shell=bash
# Shared helpers of the tool tests (sourced; W, PYRUN set by the caller).
#   fail MSG        print FAIL: MSG on stderr, exit 1
#   ok MSG          count a passed check and print it
#   py TOOL ARGS... run a tool of the package (python -m mdrmap TOOL) through
#                   tools/pyrun; py SCRIPT.py ARGS... a script
#   run NAME CMD... CMD must exit 0 without a traceback; stdout in $W/NAME.out,
#                   stderr in $W/NAME.err
#   tool_test_args SUBDIR MDRMAP_EXE PYRUN SRCDIR WORKDIR
#                   checks and sets MDRMAP, PYRUN (relative to SRCDIR if need
#                   be), SRCDIR, WORKDIR, and W = WORKDIR/SUBDIR, made empty
#   allow_mpi_here  mpirun may oversubscribe and run as root (these tests only)
#   expect_in NAME FILE TEXT
#                   FILE contains TEXT
#   refuses NAME EXPECTED CMD...
#                   CMD -o $W/bad.png exits 2 with one stderr line containing
#                   EXPECTED (in $W/NAME.err) and writes no PNG
checks=0

tool_test_args() {
  local sub=$1
  shift
  if (($# != 4)); then
    echo "usage: bash $0 MDRMAP_EXE PYRUN SRCDIR WORKDIR" >&2
    exit 2
  fi
  MDRMAP=$1 PYRUN=$2 SRCDIR=$3 WORKDIR=$4
  if [[ "$PYRUN" != /* && ! -e "$PYRUN" && -e "$SRCDIR/$PYRUN" ]]; then
    PYRUN="$SRCDIR/$PYRUN"
  fi
  [[ -x "$MDRMAP" ]] || fail "no executable $MDRMAP"
  [[ -e "$PYRUN" ]] || fail "no $PYRUN"
  W="$WORKDIR/$sub"
  rm -rf "$W"
  mkdir -p "$W"
}

allow_mpi_here() {
  command -v mpirun >/dev/null || fail "no mpirun on PATH"
  export OMPI_MCA_rmaps_base_oversubscribe=1
  if [[ "$(id -u)" == 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
}

fail() {
  echo "FAIL: $*" >&2
  exit 1
}
ok() {
  checks=$((checks + 1))
  echo "ok $checks: $*"
}
py() {
  if [[ "$1" != */* && "$1" != *.py ]]; then
    bash "$PYRUN" -m mdrmap "$@"
  else
    bash "$PYRUN" "$@"
  fi
}

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

# expect_in NAME FILE TEXT: FILE contains TEXT
expect_in() {
  grep -qF -- "$3" "$2" || {
    cat "$2" >&2
    fail "$1: '$3' not in $2"
  }
}

refuses() {
  local name=$1 expected=$2 rc=0 lines
  shift 2
  rm -f "$W/bad.png"
  "$@" -o "$W/bad.png" >"$W/$name.out" 2>"$W/$name.err" || rc=$?
  lines=$(wc -l <"$W/$name.err")
  if ((rc != 2)) || ((lines != 1)) || ! grep -qF -- "$expected" "$W/$name.err"; then
    cat "$W/$name.err" >&2
    fail "$name: expected exit 2 and one stderr line with '$expected', got exit $rc, $lines lines"
  fi
  [[ ! -e "$W/bad.png" ]] || fail "$name: wrote a PNG"
}
