#!/usr/bin/env bash
# material_card.sh ...: a study whose [run] material is a card
# (jobs/examples/card_study.ini beside rubber_card.inp, run from another
# directory: the card's path is relative to the config's) records the card's
# text in its map (/provenance/material_card), resumes
# with the same card, and refuses --resume with a changed card (exit 2, one
# line, the map unchanged) and a missing card (nothing created).
source "$(dirname "$0")/common.sh"
dir="$WORKDIR/material_card"
rm -rf "$dir"
mkdir -p "$dir/study" "$dir/elsewhere"
cp "$SRCDIR/jobs/examples/card_study.ini" "$SRCDIR/jobs/examples/rubber_card.inp" "$dir/study/"
cd "$dir/elsewhere"
map="$dir/card.h5"
study 2 --config ../study/card_study.ini --output "$map"
"${CHECK[@]}" --complete --expect-failed 0 "$map" >/dev/null
cat >"$dir/check_card.py" <<'PY'
import sys
import h5py
with h5py.File(sys.argv[1], "r") as f, open(sys.argv[2], "rb") as card:
    stored = bytes(f["provenance/material_card"][:])
    assert stored == card.read(), "the map's card differs from the file"
    # the card's spectrum is in /cases: G0 = 15 / 3, G = G0 (1 - 0.8), G1 = 0.2 G0, G2 = 0.6 G0
    for name, value in (("G", 1.0), ("G1", 1.0), ("tau1", 0.5), ("G2", 3.0), ("tau2", 20.0)):
        got = f["cases/" + name][:]
        assert abs(got - value).max() < 1e-12 * value, (name, got)
PY
"$PYRUN" "$dir/check_card.py" "$map" "$dir/study/rubber_card.inp"
study 2 --config ../study/card_study.ini --output "$map" --resume
refused() { # refused WORD ARGS...: exit 2, one line from mdrmap with WORD, the map unchanged
  local word=$1 before code=0
  shift
  before=$(sha256sum "$map")
  "$MDRMAP" study --quiet "$@" 2>"$dir/err" || code=$?
  [[ $code == 2 ]] || fail "exit $code for: $* (expected 2): $(cat "$dir/err")"
  [[ $(wc -l <"$dir/err") == 1 ]] || fail "not one line: $(cat "$dir/err")"
  grep -q -- "$word" "$dir/err" || fail "message lacks '$word': $(cat "$dir/err")"
  [[ "$before" == "$(sha256sum "$map")" ]] || fail "the map changed: $*"
  echo "refused as expected: $(cat "$dir/err")"
}
# the card's text is compared: a change that gives the same moduli is another study too
sed -i 's/name=FilledRubber/name=Other/' "$dir/study/rubber_card.inp"
refused "now '| \*Material, name=Other'" --config ../study/card_study.ini --output "$map" --resume
rm "$dir/study/rubber_card.inp"
refused "run.material" --config ../study/card_study.ini --output "$dir/new.h5"
[[ ! -e "$dir/new.h5" ]] || fail "a refused study created its map"
echo "PASS: material card"
