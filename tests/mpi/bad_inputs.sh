#!/usr/bin/env bash
# bad_inputs.sh MPIEXEC MDRMAP PYRUN SRCDIR WORKDIR: every row of bad_inputs.tsv
# is a bad input to `mdrmap study`. Each must exit 2 with exactly one line from
# mdrmap that names the problem (the table's key and problem words), with no
# HDF5 error stack, crash or nan, and must leave every file of its scratch
# directory (configs, CSV files, an existing map, a file that is not a map)
# unchanged and create none. Rows run in their own directories, several at a
# time: mpirun takes about 2 s to return after a rank exits with an error.
#
# Environment: BAD_INPUTS_JOBS (rows at a time, default 12), BAD_INPUTS_ROWS
# (only these row numbers, e.g. "3 17"; for debugging).
# shellcheck source-path=SCRIPTDIR source=common.sh
source "$(dirname "$0")/common.sh"

here=$(cd "$(dirname "$0")" && pwd)
table=$here/bad_inputs.tsv
fixtures=$here/bad_inputs
jobs=${BAD_INPUTS_JOBS:-12}
row_timeout=30 # seconds; a row normally takes under 3 s
MDRMAP=$(realpath "$MDRMAP")
MPIEXEC=$(command -v "$MPIEXEC")
scratch=$(realpath "$WORKDIR")/bad_inputs
nobody=(setpriv --reuid=65534 --regid=65534 --clear-groups)
is_root=false
[[ "$(id -u)" == 0 ]] && is_root=true

# uid 65534 (the no-permission row, as root) must reach the binary: from a
# checkout inside a mode-700 directory (mktemp -d, many home directories) it
# cannot, so it runs a copy in a directory of its own under /tmp.
nobody_mdrmap=$MDRMAP nobody_skip="" nobody_bin=""
if $is_root && command -v setpriv >/dev/null && ! "${nobody[@]}" test -x "$MDRMAP"; then
  nobody_bin=$(mktemp -d /tmp/mdrmap-bad-inputs-bin.XXXXXX)
  trap 'rm -rf "$nobody_bin"' EXIT
  # (with the programs it runs for study and fit)
  cp "$MDRMAP" "$nobody_bin/mdrmap" && cp "$(dirname "$MDRMAP")"/mdrmap-{study,fit} "$nobody_bin/" &&
    chmod 755 "$nobody_bin" "$nobody_bin"/mdrmap*
  nobody_mdrmap=$nobody_bin/mdrmap
  "${nobody[@]}" test -x "$nobody_mdrmap" ||
    nobody_skip="uid 65534 can execute neither $MDRMAP nor a copy in $nobody_bin"
fi

# A fresh scratch directory (a previous run may have left a read-only one).
if [[ -e "$scratch" ]]; then
  chmod -R u+rwX "$scratch"
  rm -rf "$scratch"
fi
mkdir -p "$scratch/fixture" "$scratch/rows" "$scratch/logs"
logs=$scratch/logs

# The files every row starts from.
fixture=$scratch/fixture
cp "$fixtures"/* "$fixture/"
(cd "$fixture" && "$MDRMAP" study --quiet --config ok.ini --output map.h5) 2>"$logs/fixture.err" ||
  fail "cannot make the fixture map: $(cat "$logs/fixture.err")"
cp "$fixture/map.h5" "$fixture/ok.h5" # the default output of --config ok.ini
head -c 3000 "$fixture/map.h5" >"$fixture/trunc.h5"
echo "not a map" >"$fixture/notes.txt"
mkdir "$fixture/adir"
# a map whose first status byte is 7, a value no study writes
cp "$fixture/map.h5" "$fixture/status7.h5"
"$PYRUN" "$here/set_status.py" "$fixture/status7.h5" 0 7 || fail "cannot make status7.h5"
# map paths that are not regular files: a FIFO (opening it would wait
# forever), links to it and to a device, and as root a device node
mkfifo "$fixture/fifo"
ln -s fifo "$fixture/fifolink"
ln -s /dev/null "$fixture/devlink"
root_skip="not root: mknod of a device node needs root"
if $is_root; then
  root_skip=""
  mknod "$fixture/dev" c 1 3 2>"$logs/mknod.err" || root_skip="mknod failed: $(cat "$logs/mknod.err")"
fi

snapshot() { # snapshot DIR: every entry with its type, then every file's sha256
  (
    cd "$1" || exit 1
    find . -printf '%y %p\n' | LC_ALL=C sort
    find . -type f -exec sha256sum {} + | LC_ALL=C sort -k 2
  )
}
fixture_before=$(snapshot "$fixture")

# run_row N HOW KEY PROBLEM ARGS...: runs one row in its own copy of the
# fixture; writes "ok" or the reasons it failed to $logs/N.verdict.
run_row() {
  set +e
  # Open MPI's session directory goes under TMPDIR: one for each row, as
  # mpiruns that start together race to create a shared one. Short, for the
  # path length limit of its sockets.
  local rowtmp tmpdir=""
  rowtmp=$(mktemp -d /tmp/mdrmap-bad-inputs.XXXXXX)
  check_row "$@"
  rm -rf "$rowtmp"
  [[ -z $tmpdir ]] || rm -rf "$tmpdir"
}

# check_row N HOW KEY PROBLEM ARGS...: the body of run_row; may set tmpdir.
check_row() {
  local n=$1 how=$2 key=$3 problem=$4
  shift 4
  local dir=$scratch/rows/$n out=$logs/$n.out err=$logs/$n.err verdict=$logs/$n.verdict
  local launch=("$MPIEXEC" -np 2) why=() exe=$MDRMAP
  mkdir -p "$dir" && cp -a "$fixture/." "$dir/"
  if [[ $how == single ]]; then
    launch=()
  elif [[ $how == root && -n $root_skip ]]; then
    echo "skip: $root_skip" >"$verdict"
    return
  elif [[ $how == nobody ]] && ! $is_root; then
    chmod 555 "$dir"
    if [[ -w $dir ]]; then
      echo "setup: $dir is still writable after chmod 555" >"$verdict"
      return
    fi
  elif [[ $how == nobody ]]; then
    if [[ -n $nobody_skip ]]; then
      echo "skip: $nobody_skip" >"$verdict"
      return
    fi
    exe=$nobody_mdrmap
    if ! command -v setpriv >/dev/null; then
      echo "setup: setpriv (util-linux) is needed to run this row as uid 65534" >"$verdict"
      return
    fi
    chmod -R a+rX "$dir"
    chmod 1777 "$rowtmp"
    if ! "${nobody[@]}" test -r "$dir/ok.ini"; then
      # uid 65534 cannot reach WORKDIR (e.g. under /root): use /tmp for this row
      tmpdir=$(mktemp -d /tmp/mdrmap-bad-inputs.XXXXXX)
      chmod 755 "$tmpdir"
      cp -a "$dir/." "$tmpdir/"
      dir=$tmpdir
    fi
    if "${nobody[@]}" test -w "$dir"; then
      echo "setup: uid 65534 can write $dir" >"$verdict"
      return
    fi
    launch=("${nobody[@]}" "${launch[@]}")
  fi
  local before after code=0
  before=$(snapshot "$dir")
  (
    cd "$dir" && export TMPDIR="$rowtmp" &&
      exec timeout -k 5 "$row_timeout" "${launch[@]}" "$exe" study --quiet "$@"
  ) </dev/null >"$out" 2>"$err" || code=$?
  [[ $how == nobody ]] && ! $is_root && chmod 755 "$dir"
  after=$(snapshot "$dir")

  # 1. exit code 2
  if [[ $code == 124 || $code == 137 ]]; then
    why+=("no exit within ${row_timeout} s (hang?)")
  elif [[ $code != 2 ]]; then
    why+=("exit $code, expected 2")
  fi
  # 2. one line from mdrmap that names the problem (mpirun adds its own lines)
  local count line
  count=$(grep -c '^mdrmap' "$err")
  line=$(grep -m 1 '^mdrmap' "$err")
  if [[ $count != 1 ]]; then
    why+=("$count lines start with 'mdrmap', expected 1")
  fi
  if [[ $how == single && $(wc -l <"$err") != 1 ]]; then
    why+=("without mpirun, stderr must be that one line")
  fi
  if [[ -n $line ]] && ! grep -qF -- "$key" <<<"$line"; then
    why+=("the message lacks the key: $key")
  fi
  if [[ -n $line && $problem != - ]] && ! grep -qF -- "$problem" <<<"$line"; then
    why+=("the message lacks the problem: $problem")
  fi
  if [[ -s $out ]]; then
    why+=("stdout is not empty: $(head -c 200 "$out")")
  fi
  # 3. nothing created or changed
  if [[ "$before" != "$after" ]]; then
    local changes
    changes=$(diff <(echo "$before") <(echo "$after") | grep '^[<>]' | head -n 6 | tr '\n' ' ')
    why+=("files changed: $changes")
  fi
  if [[ -n $(find "$dir" -name '*.tmp-*') ]]; then
    why+=("left temporary files: $(find "$dir" -name '*.tmp-*' | tr '\n' ' ')")
  fi
  # 4. no HDF5 error stack, crash, abort or nan (user text in quotes aside)
  local bad
  bad=$(grep -E -m 3 'HDF5-DIAG|Segmentation|Abort|MPI_ABORT|terminate called|core dumped' "$err")
  [[ -z $bad ]] || why+=("stderr has: $(tr '\n' ' ' <<<"$bad")")
  if sed "s/'[^']*'//g" "$err" | grep -qiw nan; then
    why+=("stderr has 'nan'")
  fi

  if ((${#why[@]} == 0)); then
    printf 'ok\n%s\n' "$line" >"$verdict"
  else
    {
      printf '%s; ' "${why[@]}"
      echo
      echo "stderr: $(head -c 600 "$err" | tr '\n' '|')"
    } >"$verdict"
  fi
}

# Read the table and run the rows, $jobs at a time.
whats=()
n=0 running=0
while IFS=$'\t' read -r what how args key problem extra; do
  [[ -z $what || $what == \#* ]] && continue
  n=$((n + 1))
  whats[n]=$what
  if [[ -z $problem || -n $extra || ! $how =~ ^(mpi|single|nobody|root)$ ]]; then
    echo "table row $n ($what): need 5 TAB-separated columns and how = mpi|single|nobody|root" \
      >"$logs/$n.verdict"
    continue
  fi
  if [[ -n ${BAD_INPUTS_ROWS:-} && " $BAD_INPUTS_ROWS " != *" $n "* ]]; then
    echo skip >"$logs/$n.verdict"
    continue
  fi
  read -r -a argv <<<"$args"
  for i in "${!argv[@]}"; do
    [[ ${argv[i]} == '{empty}' ]] && argv[i]=''
  done
  run_row "$n" "$how" "$key" "$problem" "${argv[@]}" &
  running=$((running + 1))
  if ((running >= jobs)); then
    wait -n || true
    running=$((running - 1))
  fi
done <"$table"
wait

# Report every row, in table order.
failed=0 passed=0
for ((i = 1; i <= n; i++)); do
  verdict=$logs/$i.verdict
  if [[ ! -s $verdict ]]; then
    printf 'FAIL  %d  %s: no verdict (the row did not finish)\n' "$i" "${whats[i]}"
    failed=$((failed + 1))
  elif [[ $(head -n 1 "$verdict") == skip ]]; then
    continue
  elif [[ $(head -n 1 "$verdict") == skip:* ]]; then
    printf 'skip  %d  %s: %s\n' "$i" "${whats[i]}" "$(head -n 1 "$verdict" | cut -c7-)"
  elif [[ $(head -n 1 "$verdict") == ok ]]; then
    printf 'ok  %d  %s: %s\n' "$i" "${whats[i]}" "$(sed -n 2p "$verdict")"
    passed=$((passed + 1))
  else
    printf 'FAIL  %d  %s: %s\n      %s\n' "$i" "${whats[i]}" "$(sed -n 1p "$verdict")" \
      "$(sed -n 2p "$verdict")"
    failed=$((failed + 1))
  fi
done

# The fixture and the rest of the scratch directory are untouched too.
[[ "$(snapshot "$fixture")" == "$fixture_before" ]] || {
  echo "FAIL: the fixture directory changed"
  failed=$((failed + 1))
}
leftovers=$(find "$scratch" -name '*.tmp-*')
[[ -z $leftovers ]] || {
  echo "FAIL: temporary files left: $leftovers"
  failed=$((failed + 1))
}
if [[ -z ${BAD_INPUTS_ROWS:-} ]] && ((n < 45)); then
  echo "FAIL: the table has $n rows, fewer than 45"
  failed=$((failed + 1))
fi
((failed == 0)) || fail "$failed of $n bad inputs not handled as expected (see above)"
echo "PASS: $passed bad inputs"
