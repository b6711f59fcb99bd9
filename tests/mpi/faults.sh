#!/usr/bin/env bash
# faults.sh ... SHIM CONFIG REFERENCE PART: fault injection on mdrmap study.
# PART is one of write, limit, small_fs, resume (one CTest test each):
#
#  1. A write to the map fails mid-run (below the program: the LD_PRELOAD
#     library SHIM makes pwrite fail with ENOSPC or EIO) on rank 1, on rank 0,
#     on every rank; then fsync fails at the end. Each time: exit 1, one error
#     line naming the cause and the resume command, a valid map whose done
#     rows equal the reference, and --resume (fault gone) completes it to the
#     reference bit for bit.
#  2. A file-size limit (ulimit -f) below the map's size: refused before
#     anything is written (exit 2, no file, no temporary).
#  3. A small file system (tmpfs; skipped, exit 77, where this user may not
#     mount one, e.g. not root; CI runs as root): a map that
#     does not fit is refused before anything is written; a map created
#     before the disk filled up completes on --resume with 0 bytes free,
#     because every dataset is allocated when the map is created.
#  4. --resume on damaged or foreign files: refused (exit 2), file unchanged.
source "$(dirname "$0")/common.sh"
shim=$1 config=$2 ref=$3 part=$4
[[ -f "$shim" ]] || fail "no fault library $shim"
dir="$WORKDIR/faults_$part"
rm -rf "$dir"
mkdir -p "$dir"
cd "$dir" || exit 1
STATUS=("$PYRUN" "$SRCDIR/tests/fault/map_status.py")

run() { # run OUT ERRFILE NP [mpirun -x ...] -- [study args]: exit code in $code
  local out=$1 err=$2 np=$3
  shift 3
  local mpiargs=()
  while [[ $1 != -- ]]; do
    mpiargs+=("$1")
    shift
  done
  shift
  code=0
  "$MPIEXEC" -np "$np" ${mpiargs[@]+"${mpiargs[@]}"} "$MDRMAP" study --quiet --config "$config" \
    --output "$out" "$@" 2>"$err" || code=$?
}

mdrmap_lines() { grep '^mdrmap' "$1" || true; }

# -- 1. write faults ----------------------------------------------------------------
write_fault() { # write_fault NAME RANK ERRNO FSYNC WORD
  local name=$1 rank=$2 errno=$3 fsync=$4 word=$5
  local out="$dir/$name.h5" err="$dir/$name.err"
  rm -f "$out"
  run "$out" "$err" 2 -x LD_PRELOAD="$shim" -x MDRMAP_FAULT_PATH="$out" -x MDRMAP_FAULT_SKIP=300 \
    -x MDRMAP_FAULT_RANK="$rank" -x MDRMAP_FAULT_ERRNO="$errno" -x MDRMAP_FAULT_FSYNC="$fsync" --
  local line
  line=$(mdrmap_lines "$err")
  [[ $code == 1 ]] || fail "$name: exit $code (expected 1): $(cat "$err")"
  [[ $(printf '%s\n' "$line" | wc -l) == 1 ]] || fail "$name: not one mdrmap line: $(cat "$err")"
  for w in "$word" "--resume" "rank"; do
    grep -q -- "$w" <<<"$line" || fail "$name: message lacks '$w': $line"
  done
  if grep -Eq 'HDF5-DIAG|Segmentation|MPI_ABORT|core dumped' "$err"; then
    fail "$name: crash or HDF5 dump: $(cat "$err")"
  fi
  "${CHECK[@]}" --quiet "$out" || fail "$name: map invalid after the fault"
  "${COMPARE[@]}" --done-only "$out" "$ref" >/dev/null || fail "$name: done rows differ from the reference"
  local counts
  counts=$("${STATUS[@]}" "$out")
  echo "$name: $line"
  echo "  after the fault: $counts"
  if [[ $fsync == 0 ]]; then
    # the fault struck mid-run: some rows done, some pending
    [[ $counts =~ done=([0-9]+)\ failed=0\ pending=([0-9]+) ]] || fail "$name: counts $counts"
    ((BASH_REMATCH[1] > 0 && BASH_REMATCH[2] > 0)) || fail "$name: fault not mid-run: $counts"
  fi
  run "$out" "$err" 2 -- --resume
  [[ $code == 0 ]] || fail "$name: resume exit $code: $(cat "$err")"
  "${CHECK[@]}" --quiet --complete "$out" || fail "$name: resumed map incomplete"
  "${COMPARE[@]}" "$out" "$ref" >/dev/null || fail "$name: resumed map differs from the reference"
  echo "  resumed: complete, equal to the reference"
}
part_write() {
  write_fault enospc_rank1 1 ENOSPC 0 "No space left on device"
  write_fault eio_rank0 0 EIO 0 "Input/output error"
  write_fault enospc_all "" ENOSPC 0 "No space left on device"
  write_fault fsync_eio_rank0 0 EIO 1 "flushing"
}

# -- 2. file-size limit --------------------------------------------------------------
part_limit() {
  out="$dir/limited.h5"
  code=0
  (
    # 16 MiB (Open MPI itself needs some: its shared-memory files obey the
    # limit too); the map with time series of 1001 samples needs far more
    ulimit -f 16384
    "$MPIEXEC" -np 2 "$MDRMAP" study --quiet --config "$config" --output "$out" --timeseries true \
      --samples 1001
  ) 2>"$dir/limited.err" || code=$?
  line=$(mdrmap_lines "$dir/limited.err")
  [[ $code == 2 ]] || fail "ulimit -f: exit $code (expected 2): $(cat "$dir/limited.err")"
  grep -q "file-size limit" <<<"$line" || fail "ulimit -f: message: $line"
  compgen -G "$dir/limited.h5*" >/dev/null && fail "ulimit -f: a file was written: $(ls "$dir")"
  echo "ulimit -f 16384: $line"
}

# -- 3. small file system --------------------------------------------------------------
part_small_fs() {
  mnt="$dir/small_fs"
  mkdir -p "$mnt"
  if [[ $(id -u) != 0 ]] || ! mount -t tmpfs -o size=16m mdrmap-test "$mnt" 2>/dev/null; then
    echo "SKIPPED: cannot mount a tmpfs here (needs root; CI runs it)"
    exit 77
  fi
  trap 'umount "$mnt" 2>/dev/null || true' EXIT
  # a map that cannot fit (the reference config with time series of 1001
  # samples: far more than 16 MiB)
  out="$mnt/too_big.h5"
  run "$out" "$dir/too_big.err" 2 -- --timeseries true --samples 1001
  line=$(mdrmap_lines "$dir/too_big.err")
  [[ $code == 2 ]] || fail "small fs: exit $code (expected 2): $(cat "$dir/too_big.err")"
  grep -q "free" <<<"$line" || fail "small fs: message: $line"
  [[ -z $(ls -A "$mnt") ]] || fail "small fs: files written: $(ls -A "$mnt")"
  echo "16 MiB file system, a larger map: $line"
  # a map that fits, stopped by a fault, then the disk fills up
  out="$mnt/filled.h5"
  run "$out" "$dir/filled.err" 2 -x LD_PRELOAD="$shim" -x MDRMAP_FAULT_PATH="$out" -x MDRMAP_FAULT_SKIP=300 --
  [[ $code == 1 ]] || fail "small fs: fault run exit $code: $(cat "$dir/filled.err")"
  dd if=/dev/zero of="$mnt/filler" bs=64k 2>/dev/null || true # until ENOSPC
  free=$(df --output=avail -B1 "$mnt" | tail -1 | tr -d ' ')
  [[ $free -lt 65536 ]] || fail "small fs: not full ($free bytes free)"
  echo "  file system full ($free bytes free) with $("${STATUS[@]}" "$out")"
  run "$out" "$dir/filled.err" 2 -- --resume
  [[ $code == 0 ]] || fail "small fs: resume on a full disk: exit $code: $(cat "$dir/filled.err")"
  "${COMPARE[@]}" "$out" "$ref" >/dev/null || fail "small fs: resumed map differs from the reference"
  echo "  resumed on the full file system: complete, equal to the reference"
  umount "$mnt"
  trap - EXIT
}

# -- 4. --resume on damaged and foreign files -------------------------------------------
part_resume() {
  partial="$dir/partial.h5"
  rm -f "$partial"
  run "$partial" "$dir/partial.err" 2 -x LD_PRELOAD="$shim" -x MDRMAP_FAULT_PATH="$partial" \
    -x MDRMAP_FAULT_SKIP=300 --
  [[ $code == 1 ]] || fail "partial map: exit $code"
  mapfile -t damaged < <("$PYRUN" "$SRCDIR/tests/fault/damage_map.py" "$partial" "$dir/damaged")
  [[ ${#damaged[@]} -ge 10 ]] || fail "damage_map.py made ${#damaged[@]} files"
  for f in "${damaged[@]}"; do
    before=$(sha256sum "$f")
    run "$f" "$dir/damaged.err" 2 -- --resume
    line=$(mdrmap_lines "$dir/damaged.err")
    [[ $code == 2 ]] || fail "resume $(basename "$f"): exit $code (expected 2): $(cat "$dir/damaged.err")"
    [[ $(printf '%s\n' "$line" | wc -l) == 1 ]] || fail "resume $(basename "$f"): $(cat "$dir/damaged.err")"
    grep -q -- "--resume" <<<"$line" || fail "resume $(basename "$f"): message: $line"
    [[ "$before" == "$(sha256sum "$f")" ]] || fail "resume $(basename "$f") changed the file"
    grep -q 'HDF5-DIAG' "$dir/damaged.err" && fail "resume $(basename "$f"): HDF5 error dump"
    echo "resume $(basename "$f"): $line"
  done
  # a map being written by a running job: a second job's --resume is refused
  local busy="$dir/busy.h5"
  rm -f "$busy"
  "$MPIEXEC" -np 1 "$MDRMAP" study --quiet --config "$config" --output "$busy" 2>"$dir/busy1.err" &
  local first=$!
  for _ in $(seq 200); do
    [[ -f "$busy" ]] && break
    sleep 0.05
  done
  sleep 0.3
  local before
  before=$("${STATUS[@]}" "$busy")
  run "$busy" "$dir/busy2.err" 2 -- --resume
  local first_code=0
  wait "$first" || first_code=$?
  line=$(mdrmap_lines "$dir/busy2.err")
  [[ $code == 2 ]] || fail "concurrent resume: exit $code (expected 2): $(cat "$dir/busy2.err")"
  grep -q "another mdrmap job" <<<"$line" || fail "concurrent resume: message: $line"
  [[ $first_code == 0 ]] || fail "the running job failed ($first_code): $(cat "$dir/busy1.err")"
  "${COMPARE[@]}" "$busy" "$ref" >/dev/null || fail "the running job's map differs from the reference"
  echo "resume of a map in use ($before): $line"
  echo "  the running job completed its map, equal to the reference"
}

case $part in
write | limit | small_fs | resume) "part_$part" ;;
*) fail "unknown part '$part'" ;;
esac
echo "PASS: faults ($part)"
