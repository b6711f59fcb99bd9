#!/usr/bin/env bash
# End-to-end test of the history tools (python -m mdrmap steps, python -m
# mdrmap healing), which compute their runs with mdrmap.simulate in process.
#
#   bash tests/tools/test_history_tools.sh MDRMAP_EXE PYRUN SRCDIR WORKDIR
#
# Checks:
#   - --help of each tool exits 0 and prints a usage line;
#   - at fixed depth (docs/design.md, "Histories at fixed depth"): a step up
#     reaches the new stationary state at once (no 1/e decay: D_c nan, b = 0),
#     a step down has b < 0, and a reslide after a hold of any length has no
#     peak (dmu_peak = 0 for every hold);
#   - the tools' a and a-b equal mdrmap's own event metrics of the same CSVs;
#   - under load (--F0): every run's F_N is F0, the runs have settled, and the
#     tools' a, a-b equal the event metrics (whose stationary states must then
#     be those under load); mu just after a reslide from a 1000 tau hold equals
#     its closed form (reslide out of the Hertz contact, d continuous);
#   - --from-csv reads the kept CSVs back to the same table, and a kept CSV
#     equals, row for row and event for event, what `mdrmap simulate` prints
#     for the case of its '# case' line;
#   - with a spectrum (--prony, --tau 0) the tools run, their a and a-b
#     equal the event metrics, and --from-csv refuses another spectrum;
#   - every PNG starts with the PNG signature and has a drawn size;
#   - bad invocations exit 2 with exactly one line on stderr, no traceback,
#     and write no PNG.
set -euo pipefail

# shellcheck source=tests/tools/lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
tool_test_args history_tools_test "$@"
ST=steps
HE=healing

# bad NAME EXPECTED CMD...: refuses (lib.sh), counted as a passed check
bad() {
  refuses "$@"
  ok "bad input refused: $1"
}

# png FILE: PNG signature and a drawn size
png() {
  [[ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" == 89504e470d0a1a0a ]] || fail "$1: not a PNG"
  (($(stat -c %s "$1") > 20000)) || fail "$1: too small for a drawn figure"
  ok "$(basename "$1") is a drawn PNG"
}

# table_value FILE ZETA STEP COLUMN: a value of the steps table
table_value() {
  awk -v z="$2" -v s="$3" -v c="$4" '
    $1 == "zeta0" && $2 == "step" { for (i = 1; i <= NF; i++) col[$i] = i; next }
    $1 == z && $2 == s { print $(col[c]) }' "$1"
}

# event_check CSVDIR TABLE: the tools' a and a-b (units of mu_ref) equal the
# CSV's own event line (units of mu) to the 4 digits printed
event_check() {
  local dir=$1 table=$2 f z s
  for f in "$dir"/step_*.csv; do
    z=$(basename "$f" .csv | cut -d_ -f3)
    s=$(basename "$f" .csv | cut -d_ -f2)
    awk -v ta="$(table_value "$table" "$z" "$s" a)" -v tab="$(table_value "$table" "$z" "$s" a-b)" '
      /^# case / { for (i = 3; i <= NF; i++) { split($i, kv, "="); c[kv[1]] = kv[2] } }
      /^# event / { for (i = 3; i <= NF; i++) { split($i, kv, "="); e[kv[1]] = kv[2] } }
      END {
        ref = ("a0" in c) ? c["a0"] / c["R"] : sqrt(c["d"] / c["R"])
        bad = 0
        if (ta == "" || tab == "") bad = 1
        else {
          if (abs(e["a"] / ref - ta) > 1e-3 * abs(ta) + 1e-12) bad = 1
          if (abs(e["a_minus_b"] / ref - tab) > 1e-3 * abs(tab) + 1e-12) bad = 1
        }
        if (bad) { printf "event a=%s a_minus_b=%s (scale %s) vs table a=%s a-b=%s\n", e["a"], e["a_minus_b"], ref, ta, tab; exit 1 }
      }
      function abs(x) { return x < 0 ? -x : x }' "$f" || fail "$f: the tool's a, a-b differ from the event line"
  done
  ok "$(basename "$dir"): the tools' a and a-b equal mdrmap's event metrics"
}

for tool in "$ST" "$HE"; do
  run help py "$tool" --help
  grep -q "^usage: " "$W/help.out" || fail "$tool --help: no usage line"
  ok "$(basename "$tool") --help"
done

# ------------------------------------------------------------ fixed depth
run steps_depth py "$ST" --d 0.01 --R 100 --samples 41 \
  --csv-dir "$W/steps_depth" -o "$W/steps_depth.png"
png "$W/steps_depth.png"
for z in 0.1 1 10; do
  [[ "$(table_value "$W/steps_depth.out" "$z" up D_c)" == nan ]] || fail "fixed depth, step up at $z: D_c not nan"
  b=$(table_value "$W/steps_depth.out" "$z" up b)
  awk -v b="$b" 'BEGIN { exit !(b < 1e-12 && b > -1e-12) }' || fail "fixed depth, step up: b = $b, not 0"
  b=$(table_value "$W/steps_depth.out" "$z" down b)
  awk -v b="$b" 'BEGIN { exit !(b < 0) }' || fail "fixed depth, step down at $z: b = $b, not < 0"
done
ok "fixed depth: a step up is stationary at once (D_c nan, b = 0), a step down has b < 0"
event_check "$W/steps_depth" "$W/steps_depth.out"

run steps_depth_reread py "$ST" --d 0.01 --R 100 --samples 41 --csv-dir "$W/steps_depth" --from-csv
cmp -s <(grep -v '^wrote' "$W/steps_depth.out") "$W/steps_depth_reread.out" ||
  fail "--from-csv gives another table"
ok "--from-csv reads the kept CSVs back to the same table"

run healing_depth py "$HE" --d 0.01 --R 100 --samples 31 --holds 0.1,10,1000 \
  -o "$W/healing_depth.png"
png "$W/healing_depth.png"
awk '/^ *[0-9.e+-]+ +[0-9.e+-]+ / { n++; if ($2 + 0 > 1e-12 || $2 + 0 < -1e-12) bad = 1 }
     END { exit !(n == 3 && !bad) }' "$W/healing_depth.out" ||
  fail "fixed depth: a reslide shows a peak ($(cat "$W/healing_depth.out"))"
ok "fixed depth: no peak after a hold of 0.1, 10 or 1000 tau"

# ------------------------------------------------------------ load control
# F0 = 16/3 G a0^3 / R with a0 = 1, R = 100
F0=0.053333333333333333
run steps_load py "$ST" --F0 $F0 --R 100 --samples 41 --rtol 1e-3 \
  --csv-dir "$W/steps_load" -o "$W/steps_load.png"
png "$W/steps_load.png"
for f in "$W"/steps_load/step_*.csv; do
  awk -F, -v F0=$F0 'NR > 1 && !/^#/ && $1 != "t" { if (($3 - F0) / F0 > 1e-3 || ($3 - F0) / F0 < -1e-3) bad = 1 }
    END { exit bad }' "$f" || fail "$f: F_N differs from F0 by more than rtol"
done
ok "load control: F_N = F0 within rtol in every step run"
awk '$1 ~ /^[0-9.]+$/ && NF > 5 { if ($NF + 0 > 1e-3) bad = 1 } END { exit bad }' "$W/steps_load.out" ||
  fail "load control: a step run has not settled ($(cat "$W/steps_load.out"))"
ok "load control: every step run settles"
event_check "$W/steps_load" "$W/steps_load.out"

# (--FN: the old spelling of --F0, still taken)
run healing_load py "$HE" --FN $F0 --R 100 --samples 31 --rtol 1e-3 --holds 0.1,10,1000 \
  --zeta0 0.1,1,10 --csv-dir "$W/healing_load" -o "$W/healing_load.png"
png "$W/healing_load.png"
# After a long hold the contact is Hertz's [-a0, a0] at d0; at the reslide d
# is continuous and c = tau R d' jumps so that F0 = integral of
# p = 4G/R (a0^2 + c - x^2 - 2 w tau x) over [-a0, e], e = min(a0, root of p):
# mu(0+) in closed form (one scalar root), independent of the solver.
cat >"$W/reslide.py" <<'EOF'
import math, sys
def bisect(f, lo, hi):
    for _ in range(300):
        m = (lo + hi) / 2
        lo, hi = (m, hi) if (f(lo) < 0) == (f(m) < 0) else (lo, m)
    return (lo + hi) / 2
def mu_reslide(L):  # a0 = R = G = 1, F0 = 16/3, L = w tau / a0; mu in units of a0/R
    def forces(c):
        e = min(1.0, -L + math.sqrt(L * L + 1 + c))
        P = lambda x: (1 + c) * x - x**3 / 3 - L * x * x
        Q = lambda x: (1 + c) * x * x / 2 - x**4 / 4 - 2 * L * x**3 / 3
        return 4 * (P(e) - P(-1)), -8 * (Q(e) - Q(-1))
    c = bisect(lambda c: forces(c)[0] - 16 / 3, -2 * L, 100.0)
    FN, Fx = forces(c)
    return Fx / FN
bad = 0
for path in sys.argv[1:]:
    lines = open(path).read().splitlines()
    case = dict(t.split("=", 1) for t in next(l for l in lines if l.startswith("# case")).split()[2:])
    zeta0, ref = float(case["zeta0"]), float(case["a0"]) / float(case["R"])
    mu0 = next(float(r.split(",")[4]) for r in lines if r[:1].isdigit() and r.split(",")[1] == "1")
    want = mu_reslide(zeta0)
    ok = abs(mu0 / ref - want) <= 1e-3 * want
    print(f"zeta0={zeta0:g}: mu(0+)/(a0/R) = {mu0 / ref:.10g}, closed form {want:.10g}")
    bad += not ok
sys.exit(bad)
EOF
run reslide_check py "$W/reslide.py" "$W"/healing_load/shs_*_1000.csv
cat "$W/reslide_check.out"
ok "load control: mu just after the reslide from a 1000 tau hold matches the closed form within rtol"

# ------------------------------------------------------------ the program's CSV
# A kept CSV equals `mdrmap simulate` of the case its '# case' line names (the
# module's results are the program's bit for bit; both print round-trip digits).
cat >"$W/same.py" <<'EOF'
# pyrun-needs: numpy
import subprocess, sys
mdrmap, path = sys.argv[1:3]
def kv(ln):
    return dict(t.split("=", 1) for t in ln.split()[2:] if "=" in t)
def read(lines):
    c = [ln for ln in lines if ln.startswith("#")]
    rows = [[float(x) for x in ln.split(",")] for ln in lines if ln[:1].isdigit()]
    events = [{k: float(v) for k, v in kv(ln).items() if k != "D_c_undefined"}
              for ln in c if ln.startswith("# event ")]
    return c, rows, events
c, rows, ev = read(open(path).read().splitlines())
case = kv(next(ln for ln in c if ln.startswith("# case ")))
args = [mdrmap, "simulate", "--rtol", kv(c[0])["rtol"]]
for k, v in case.items():
    if k not in ("a0", "zeta0"):
        args += ["--" + k, v]
out = subprocess.run(args, check=True, stdout=subprocess.PIPE, text=True).stdout
_, rows2, ev2 = read(out.splitlines())
same = lambda x, y: x == y or (x != x and y != y)  # noqa: E731 (nan equals nan here)
same_events = len(ev) == len(ev2) and all(
    a.keys() == b.keys() and all(same(a[k], b[k]) for k in a) for a, b in zip(ev, ev2))
if rows != rows2 or not same_events or len(rows) < 3:
    sys.exit(f"{path}: differs from {' '.join(args)} ({len(rows)} vs {len(rows2)} rows, "
             f"events equal: {same_events})")
print(f"{path}: {len(rows)} rows and {len(ev)} events equal mdrmap simulate's")
EOF
for f in "$W"/steps_load/step_up_1.csv "$W"/healing_load/shs_1_10.csv "$W"/steps_depth/step_down_10.csv; do
  run "same_$(basename "$f" .csv)" py "$W/same.py" "$MDRMAP" "$f"
done
ok "a kept CSV equals mdrmap simulate's output for its case (rows and events)"

# ------------------------------------------------------------ spectrum
run steps_spectrum py "$ST" --d 0.01 --R 100 --tau 0 --prony 1:1,1:0.01 --samples 31 --zeta0 1 \
  --csv-dir "$W/steps_spectrum" -o "$W/steps_spectrum.png"
png "$W/steps_spectrum.png"
grep -q "prony=" "$W/steps_spectrum/step_up_1.csv" || fail "the spectrum run's CSV has no prony"
event_check "$W/steps_spectrum" "$W/steps_spectrum.out"
run healing_spectrum py "$HE" --F0 $F0 --R 100 --tau 0 --prony 1:1,1:0.01 --samples 31 \
  --holds 0.1,100 --rtol 1e-3
awk '/^ *[0-9.e+-]+ +[0-9.e+-]+ / { n++; p[n] = $2 } END { exit !(n == 2 && p[2] > p[1]) }' \
  "$W/healing_spectrum.out" ||
  fail "spectrum under load: dmu_peak does not grow with the hold ($(cat "$W/healing_spectrum.out"))"
ok "spectrum (--prony, --tau 0): steps' a, a-b equal the events; under load the peak grows with the hold"

# ------------------------------------------------------------ bad input
base=(--R 100)
bad neither "exactly one of --F0" py "$ST" "${base[@]}"
bad both "exactly one of --F0" py "$HE" --F0 1 --d 0.1 "${base[@]}"
bad both_spellings "argument --FN: not allowed with argument --F0" py "$ST" --F0 1 --FN 1 "${base[@]}"
bad F0_negative "--F0: must be" py "$ST" --F0 -1 "${base[@]}"
bad F0_nan "--F0: must be" py "$HE" --F0 nan "${base[@]}"
bad tau_zero "--tau" py "$ST" --F0 1 --tau 0 "${base[@]}"
bad zeta_text "--zeta0" py "$ST" --F0 1 --zeta0 1,abc "${base[@]}"
bad zeta_zero "--zeta0" py "$HE" --F0 1 --zeta0 0 "${base[@]}"
bad ratio_one "--ratio" py "$ST" --F0 1 --ratio 1 "${base[@]}"
bad holds_order "--holds" py "$HE" --F0 1 --holds 10,1 "${base[@]}"
bad samples "--samples" py "$HE" --F0 1 --samples 2 "${base[@]}"
bad unknown_option "unrecognized arguments" py "$ST" --F0 1 --speed 3 "${base[@]}"
bad from_csv_no_dir "--csv-dir" py "$ST" --F0 1 --from-csv "${base[@]}"
bad from_csv_missing "no such file" py "$HE" --F0 1 --from-csv --csv-dir "$W/nothing" "${base[@]}"
bad from_csv_other_case "rerun without --from-csv" py "$ST" --d 0.02 --R 100 --samples 41 \
  --csv-dir "$W/steps_depth" --from-csv
bad prony_text "--prony: not a number" py "$ST" --F0 1 --prony 1:abc "${base[@]}"
bad prony_refused "mdrmap.simulate: prony" py "$HE" --F0 1 --prony 1:-1 "${base[@]}"
bad no_mdrmap_option "unrecognized arguments: --mdrmap" py "$ST" --F0 1 --mdrmap "$MDRMAP"
bad from_csv_other_spectrum "is not the --prony asked for" py "$ST" --d 0.01 --tau 0 --prony 1:1,1:0.02 \
  --R 100 --samples 31 --csv-dir "$W/steps_spectrum" --from-csv --zeta0 1

echo "all $checks checks passed"
