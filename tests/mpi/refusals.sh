#!/usr/bin/env bash
# refusals.sh ... CONFIG OTHER_CONFIG: an existing output is never touched
# without --resume/--overwrite; --resume refuses a different study;
# --overwrite refuses a file that is not a map; each exits 2 with one line.
source "$(dirname "$0")/common.sh"
config=$1 other=$2
map="$WORKDIR/refuse.h5"
rm -f "$map"
study 1 --config "$config" --output "$map"
expect_refusal() { # expect_refusal FILE WORD ARGS...: exit 2, FILE unchanged, message has WORD
  local file=$1 word=$2
  shift 2
  local before after code=0
  before=$(sha256sum "$file")
  "$MPIEXEC" -np 2 "$MDRMAP" study --quiet "$@" 2>"$WORKDIR/refuse.err" || code=$?
  after=$(sha256sum "$file")
  [[ $code == 2 ]] || fail "exit $code for: $* (expected 2)"
  [[ "$before" == "$after" ]] || fail "$file changed by refused run: $*"
  # one line from mdrmap (mpirun adds its own notice about the exit code)
  [[ $(grep -c '^mdrmap' "$WORKDIR/refuse.err") == 1 ]] || fail "not one line: $(cat "$WORKDIR/refuse.err")"
  grep -q -- "$word" "$WORKDIR/refuse.err" || fail "message lacks '$word': $(cat "$WORKDIR/refuse.err")"
  echo "refused as expected: $(grep '^mdrmap' "$WORKDIR/refuse.err")"
}
# without a launcher (MPI singleton) the refusal is exactly one line in all
before=$(sha256sum "$map")
code=0
"$MDRMAP" study --config "$config" --output "$map" 2>"$WORKDIR/refuse1.err" || code=$?
[[ $code == 2 && $(wc -l <"$WORKDIR/refuse1.err") == 1 && "$before" == "$(sha256sum "$map")" ]] ||
  fail "singleton refusal: exit $code, stderr: $(cat "$WORKDIR/refuse1.err")"
expect_refusal "$map" "exists" --config "$config" --output "$map"
expect_refusal "$map" "differs" --config "$other" --output "$map" --resume
expect_refusal "$map" "differs" --config "$config" --output "$map" --resume --samples 7
expect_refusal "$map" "exclude" --config "$config" --output "$map" --resume --overwrite
echo "not a map" >"$WORKDIR/notes.txt"
expect_refusal "$WORKDIR/notes.txt" "refusing" --config "$config" --output "$WORKDIR/notes.txt" --overwrite
expect_refusal "$WORKDIR/notes.txt" "refusing" --config "$config" --output "$WORKDIR/notes.txt" --resume
# --overwrite replaces a map
study 2 --config "$other" --output "$map" --overwrite
"${CHECK[@]}" --complete "$map"
echo "PASS: refusals"
