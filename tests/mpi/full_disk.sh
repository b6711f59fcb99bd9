#!/usr/bin/env bash
# full_disk.sh ... SHIM PART: the end of a study whose cases partly fail, on a
# full disk and on a failing device (issue 23, class 1). 200 cases under load,
# every other one failing (w1 = 1e100); the map is made first by a run whose
# every write to it fails (all 200 pending), then resumed: that run computes
# all 200 cases and records the 100 failures' messages at its end. PART:
#
#  end_fault  The writes into /failures fail (EIO, below the program: the
#             LD_PRELOAD library SHIM, on exactly /failures' bytes), np = 1
#             and 2: exit 1, one error line, no crash; the map stays
#             readable, 100 done and 100 failed (the status column, which
#             /failures does not explain); --resume then runs
#             the unrecorded failures again and the map equals a map made in
#             one run (tools/maps/compare_maps.py).
#  full_disk  The disk is full (a 2 MiB tmpfs filled with dd after the map was
#             made; skipped, exit 77, where this user may not mount one),
#             np = 1 and 2: exit 0, no crash, the map complete and equal to
#             the one-run map, /failures readable: nothing written at the end
#             needs space that was not reserved when the map was created.
source "$(dirname "$0")/common.sh"
shim=$1 part=$2
[[ -f "$shim" ]] || fail "no fault library $shim"
dir="$WORKDIR/full_disk_$part"
rm -rf "$dir"
mkdir -p "$dir"
cd "$dir" || exit 1

cat >"$dir/cases.py" <<'EOF'
# pyrun-needs: numpy
import sys
with open(sys.argv[1], "w") as f:
    f.write("F0,R,tau,v,w1,T1\n")
    for i in range(200):
        w1 = "1e100" if i % 2 else repr(0.5 + 0.01 * i)
        f.write(f"5.333333333333333,1,1,1,{w1},1\n")
EOF
"$PYRUN" "$dir/cases.py" "$dir/cases.csv"
printf '[cases]\nfile = cases.csv\n[run]\nsamples = 5\nrtol = 1e-3\n' >"$dir/study.ini"

run() { # run ERRFILE NP [mpirun -x ...] -- [study args]: exit code in $code
  local err=$1 np=$2
  shift 2
  local mpiargs=()
  while [[ $1 != -- ]]; do
    mpiargs+=("$1")
    shift
  done
  shift
  code=0
  "$MPIEXEC" -np "$np" ${mpiargs[@]+"${mpiargs[@]}"} "$MDRMAP" study --quiet \
    --config "$dir/study.ini" "$@" 2>"$err" || code=$?
}
no_crash() { # no_crash WHAT ERRFILE
  if grep -Eq 'HDF5-DIAG|Segmentation|signal|MPI_ABORT|core dumped' "$2"; then
    fail "$1: crash or HDF5 dump: $(cat "$2")"
  fi
}
one_line() { # one_line WHAT ERRFILE: the one mdrmap line of the error file
  local line
  line=$(grep '^mdrmap' "$2" || true)
  [[ $(printf '%s\n' "$line" | grep -c .) == 1 ]] || fail "$1: not one mdrmap line: $(cat "$2")"
  printf '%s\n' "$line"
}
counts() { "$PYRUN" "$SRCDIR/tests/fault/map_status.py" "$1"; }

ref="$dir/reference.h5"
run "$dir/ref.err" 2 -- --output "$ref"
[[ $code == 0 ]] || fail "reference: exit $code: $(cat "$dir/ref.err")"
"${CHECK[@]}" --quiet --complete --expect-failed 100 "$ref" || fail "reference map"

made_pending() { # made_pending OUT NP: the map made, all its cases pending
  local out=$1 np=$2
  rm -f "$out"
  run "$dir/made.err" "$np" -x LD_PRELOAD="$shim" -x MDRMAP_FAULT_PATH="$out" -- --output "$out"
  [[ $code == 1 ]] || fail "making the map (writes fail): exit $code: $(cat "$dir/made.err")"
  no_crash "making the map" "$dir/made.err"
  [[ $(counts "$out") == "done=0 failed=0 pending=200" ]] || fail "made map: $(counts "$out")"
}

part_end_fault() {
  for np in 1 2; do
    local out="$dir/end_np$np.h5" err="$dir/end_np$np.err"
    made_pending "$out" "$np"
    cat >"$dir/bytes.py" <<'EOF'
# pyrun-needs: h5py
"""The bytes [lo:hi) of the map's /failures datasets."""
import sys
import h5py
with h5py.File(sys.argv[1], "r") as f:
    c, m = f["failures/case"].id, f["failures/message"].id
    if c.get_offset() is None or m.get_offset() is None:  # not allocated: nothing to fail
        sys.exit(print("0:0"))
    lo = min(c.get_offset(), m.get_offset())
    hi = max(c.get_offset() + c.get_storage_size(), m.get_offset() + m.get_storage_size())
print(f"{lo}:{hi}")
EOF
    local bytes
    bytes=$("$PYRUN" "$dir/bytes.py" "$out")
    run "$err" "$np" -x LD_PRELOAD="$shim" -x MDRMAP_FAULT_PATH="$out" -x MDRMAP_FAULT_ERRNO=EIO \
      -x MDRMAP_FAULT_BYTES="$bytes" -- --output "$out" --resume
    [[ $code == 1 ]] || fail "np $np, /failures write fails: exit $code (expected 1): $(cat "$err")"
    local line
    line=$(one_line "np $np, /failures write fails" "$err")
    no_crash "np $np, /failures write fails" "$err"
    for w in "failures" "Input/output error" "--resume"; do
      grep -q -- "$w" <<<"$line" || fail "np $np: message lacks '$w': $line"
    done
    # the counts: a failed case is not done, and one whose message is not
    # recorded is left for --resume
    grep -qF "100 of 200 cases are done in the map, 0 failed and recorded, 100 left for --resume" \
      <<<"$line" || fail "np $np: counts (expected 100 done, 0 recorded, 100 left): $line"
    # (not check_map.py: it wants a message for every failed case, and these
    # have none: the status column says failed, /failures does not know why)
    [[ $(counts "$out") == "done=100 failed=100 pending=0" ]] || fail "np $np: $(counts "$out")"
    echo "np $np, /failures write fails: $line"
    run "$err" "$np" -- --output "$out" --resume
    [[ $code == 0 ]] || fail "np $np: resume exit $code: $(cat "$err")"
    "${CHECK[@]}" --quiet --complete --expect-failed 100 "$out" || fail "np $np: resumed map"
    "${COMPARE[@]}" "$out" "$ref" >/dev/null || fail "np $np: resumed map differs from the one-run map"
    echo "  resumed: failures retried and recorded, the map equals the one-run map"
  done
}

part_full_disk() {
  local mnt="$dir/fs"
  mkdir -p "$mnt"
  if [[ $(id -u) != 0 ]] || ! mount -t tmpfs -o size=2m mdrmap-test "$mnt" 2>/dev/null; then
    echo "SKIPPED: cannot mount a tmpfs here (needs root; CI runs it)"
    exit 77
  fi
  trap 'umount "$mnt" 2>/dev/null || true' EXIT
  for np in 1 2; do
    local out="$mnt/full_np$np.h5" err="$dir/full_np$np.err"
    rm -f "$mnt"/*
    made_pending "$out" "$np"
    dd if=/dev/zero of="$mnt/filler" bs=16k 2>/dev/null || true # until ENOSPC
    local free
    free=$(df --output=avail -B1 "$mnt" | tail -1 | tr -d ' ')
    [[ $free == 0 ]] || fail "np $np: the file system is not full ($free bytes free)"
    run "$err" "$np" -- --output "$out" --resume
    no_crash "np $np, full disk" "$err"
    [[ $code == 0 ]] || fail "np $np, full disk: exit $code (expected 0): $(cat "$err")"
    "${CHECK[@]}" --quiet --complete --expect-failed 100 "$out" || fail "np $np: map after a full disk"
    "${COMPARE[@]}" "$out" "$ref" >/dev/null || fail "np $np: full-disk map differs from the one-run map"
    echo "np $np, 0 bytes free: exit 0, $(counts "$out"), the map equals the one-run map"
  done
  umount "$mnt"
  trap - EXIT
}

case $part in
end_fault | full_disk) "part_$part" ;;
*) fail "unknown part '$part'" ;;
esac
echo "PASS: full_disk ($part)"
