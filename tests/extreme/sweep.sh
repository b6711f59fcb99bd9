#!/usr/bin/env bash
# sweep.sh MDRMAP [WORKDIR]: mdrmap simulate over extreme histories (issue 23,
# "no input runs unbounded"): holds from 1e-300 to 1e300 tau, velocities from
# 1e-300 to 1e300, zeta0 = v tau / a from 1e-12 to 1e12, at fixed depth (--d)
# and under load (--F0), each under a fixed timeout. Every case must end in one
# of three ways:
#   exit 0  finite output (no inf/nan in the rows or the pre line), stderr empty;
#   exit 2  one stderr line naming an option ("mdrmap simulate: error: --OPT: ..."),
#           stdout empty (refused at validation);
#   exit 1  one stderr line ("mdrmap simulate: error: ...") (the case failed).
# A timeout is a failure (the case ran unbounded). Some cases also name the
# outcome they must have (e.g. 2:history). Then a few exit-0 cases are run with
# --solver row (which adds the error against a reference: the continuum solver
# at 1e-12 at fixed depth, kelvin_load at rtol/1000 under load) and must be
# within rtol with an error estimate of at least a third of the error.
#
# Environment: SWEEP_TIMEOUT (seconds per case, default 60).
# Prints one line per case and a summary: counts per outcome, seconds in all.
set -uo pipefail
MDRMAP=$1
WORK=${2:-$(mktemp -d)}
TIMEOUT=${SWEEP_TIMEOUT:-60}
mkdir -p "$WORK"
out="$WORK/sweep.out" err="$WORK/sweep.err"

DEPTH="--d 1e-3 --R 1 --v 1" # a1 = sqrt(R d) = 0.0316
LOAD="--F0 5.333333333333333 --R 1 --v 1" # a0 = 1 (G = 1)

# label | expected (any, or CODE[:option]) | arguments after "simulate"
CASES=()
add() { CASES+=("$1|$2|$3"); }
for load in depth load; do
  base=$DEPTH
  [[ $load == load ]] && base=$LOAD
  # holds of 1e-300 .. 1e300 tau, then a reslide
  for T in 1e-300 1e-12 1e12 1e300; do
    add "$load hold $T tau" any "$base --tau 1 --history 0:$T,1:1 --samples 11"
  done
  # velocities from 1e-300 to 1e300: a step from v0 = 1, and v0 itself
  for W in 1e-300 1e-12 1e12 1e300; do
    add "$load step to $W" any "$base --tau 1 --history $W:1 --samples 11"
  done
  for V in 1e-300 1e300; do
    add "$load v0 $V" any "${base/--v 1/--v $V} --tau 1 --history 1:1 --samples 11"
  done
  # zeta0 = v tau / a from 1e-12 to 1e12: slide-hold-slide, holds of 10 tau
  a=0.031622776601683791
  [[ $load == load ]] && a=1
  for z in 1e-12 1e-6 1 1e6 1e12; do
    tau=$(awk -v z="$z" -v a="$a" 'BEGIN { printf "%.17g", z * a }')
    T=$(awk -v t="$tau" 'BEGIN { printf "%.17g", 10 * t }')
    add "$load shs zeta0 $z" any "$base --tau $tau --history 0:$T,1:$T --samples 11"
  done
done
# the reproductions of issue 23 (classes 3 and 7)
add "depth sample time overflow" 0 "$DEPTH --tau 1 --history 0:1e306,1:1"
add "depth 1e308 at a1 = 1" 2:history "--d 1 --R 1 --v 1 --tau 1 --history 1e308:1"
add "load 5e307" 2:history "$LOAD --tau 1 --history 5e307:1"
# issue 32: at a0 = 0.72 these ran for ever (3 zeta0 overflowed in the bracket)
for W in 5e307 7e307 1e308; do
  add "load $W at a0 0.72" 2:history "--F0 0.2 --R 10 --v 1 --tau 1 --history $W:1 --samples 5"
done
add "load hold 1e12 tau" any "$LOAD --tau 1 --history 0:1e12,1:1 --samples 11"
add "load hold 1e18 tau" any "$LOAD --tau 1 --history 0:1e18,1:1 --samples 11"
add "load hold 3e10 tau" any "$LOAD --tau 1 --history 0:3e10,1:1 --samples 11"
add "load v 1e6 log 6 decades" any \
  "--F0 5.333333333333333 --R 1 --tau 1 --v 1e6 --history 0:1e4,1e6:1 --spacing log --log-decades 6 --rtol 1e-3"
add "load shs zeta0 1e8" any "$LOAD --tau 1e8 --history 0:1e9,1:1e9 --samples 11"

declare -A count=()
failures=0
start=$SECONDS
# shellcheck source=tests/extreme/check.sh
source "$(dirname "${BASH_SOURCE[0]}")/check.sh"

for c in "${CASES[@]}"; do
  IFS="|" read -r label expected args <<<"$c"
  t0=$(date +%s.%N)
  # shellcheck disable=SC2086  # the arguments are words
  timeout -k 5 "$TIMEOUT" "$MDRMAP" simulate $args >"$out" 2>"$err"
  code=$?
  secs=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')
  if check "$label" "$expected" "$code" simulate; then
    count["exit $code"]=$((${count["exit $code"]:-0} + 1))
    printf '%-32s exit %s  %6s s  %s\n' "$label" "$code" "$secs" "$(head -c 120 "$err")"
  else
    count[violations]=$((${count[violations]:-0} + 1))
    failures=$((failures + 1))
  fi
done

# Accuracy: exit-0 cases with --solver row, within rtol, estimate >= error / 3.
SPOT=(
  "$DEPTH --tau 1 --history 0:1e12,1:1 --samples 11 --rtol 1e-3"
  "$DEPTH --tau 1 --history 1e-12:1,1:1 --samples 11 --rtol 1e-3"
  "$DEPTH --tau 3.1622776601683791e-7 --history 0:1e-5,1:1e-5 --samples 11 --rtol 1e-3"
  "$DEPTH --tau 31622.776601683792 --history 0:1e5,1:1e5 --samples 11 --rtol 1e-3"
  "$LOAD --tau 1 --history 0:10,1:10 --samples 11 --rtol 1e-3"
)
for args in "${SPOT[@]}"; do
  # shellcheck disable=SC2086
  timeout -k 5 "$TIMEOUT" "$MDRMAP" simulate $args --solver row >"$out" 2>"$err"
  code=$?
  verdict=$(awk -v code="$code" '
    /error_estimate=/ { for (i = 1; i <= NF; i++) if ($i ~ /^(error_estimate|rtol)=/) { split($i, kv, "="); v[kv[1]] = kv[2] } }
    /^# error_vs_(exact|reference)=/ { split($2, kv, "="); err = kv[2]; have = 1 }
    END {
      if (code != 0 || !have) { print "FAIL exit " code; exit }
      ok = (err <= v["rtol"] && v["error_estimate"] >= err / 3)
      printf "%s error %.3g estimate %.3g rtol %s\n", ok ? "ok" : "FAIL", err, v["error_estimate"], v["rtol"]
    }' "$out")
  echo "spot-check row: $verdict: $args"
  if [[ $verdict != ok* ]]; then
    failures=$((failures + 1))
    count[violations]=$((${count[violations]:-0} + 1))
    head -c 300 "$err"
  fi
done

summary=""
for k in "${!count[@]}"; do summary+="$k: ${count[$k]}, "; done
echo "sweep: ${#CASES[@]} cases, ${#SPOT[@]} spot checks; ${summary}$((SECONDS - start)) s in all"
[[ $failures == 0 ]] || { echo "FAIL: $failures violations"; exit 1; }
echo "PASS"
