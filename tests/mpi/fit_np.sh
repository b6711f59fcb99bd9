#!/usr/bin/env bash
# fit_np.sh ... NP: mdrmap fit of two synthetic records under load (the
# solver's own values at R 10, aT 2 with a fixed pseudo-random 1% noise) at
# NP ranks; the result must hold the truth in its intervals and, for NP > 1,
# be the NP = 1 result number for number (only the wall time, the rank count
# and the output name differ).
source "$(dirname "$0")/common.sh"
np=$1
dir="$WORKDIR/fit"
mkdir -p "$dir"
record() { # record NAME W1:T1,W2:T2,...: a record of 8 rows a segment, measured mu and d
  local name=$1 hist="$dir/$1.hist.csv"
  if [[ ! -s "$dir/$name.csv" ]]; then
    awk -v segs="$2" 'BEGIN { print "t,v"; n = split(segs, s, ","); t = 0
      for (k = 1; k <= n; k++) { split(s[k], p, ":")
        for (j = 0; j < 8; j++) printf "%.17g,%.17g\n", t + p[2] * j / 8, p[1]
        t += p[2] }
      printf "%.17g,%.17g\n", t, p[1] }' >"$hist"
    "$MDRMAP" simulate --F0 0.1 --R 10 --tau 1 --aT 2 --rtol 1e-7 --history-file "$hist" |
      awk -F, '/^#/ { next } !h { for (i = 1; i <= NF; i++) c[$i] = i; h = 1; print "t,v,mu,d"; next }
        { r1 = (((NR * 7919) % 1000) / 1000 - 0.5) * 0.035; r2 = (((NR * 104729) % 1000) / 1000 - 0.5) * 0.035
          printf "%s,%s,%.17g,%.17g\n", $c["t"], $c["v"], $c["mu"] * (1 + r1), $c["d"] * (1 + r2) }' \
        >"$dir/$name.csv.tmp"
    mv "$dir/$name.csv.tmp" "$dir/$name.csv"
  fi
}
record a 1:2,0.1:5,1:5
record b 10:1,1:2,0.01:10
out="$dir/fit_np$np.json"
rm -f "$out"
"$MPIEXEC" -np "$np" "$MDRMAP" fit --data "$dir/a.csv" --data "$dir/b.csv" --free R,aT \
  --F0 0.1 --tau 1 --R 30 --aT 0.667 --output "$out"
inside() { # inside NAME TRUTH: the truth lies in the parameter's ci95
  grep -E "\"$1\": \{" "$out" | sed -E 's/.*"ci95": \[([^,]*), ([^]]*)\].*/\1 \2/' |
    awk -v x="$2" '{ exit !($1 <= x && x <= $2) }' || fail "np=$np: $1 = $2 outside its ci95: $(grep "\"$1\": {" "$out")"
}
inside R 10
inside aT 2
if [[ "$np" != 1 ]]; then
  diff <(grep -v -E '"(wall_seconds|ranks|command)"' "$dir/fit_np1.json") \
    <(grep -v -E '"(wall_seconds|ranks|command)"' "$out") || fail "np=$np differs from np=1"
fi
# a direction the records do not fix (F0 and G under load): exit 2 on every
# rank count, one line naming them, nothing written, no rank left waiting
flat="$dir/flat_np$np.json"
code=0
timeout 120 "$MPIEXEC" -np "$np" "$MDRMAP" fit --data "$dir/a.csv" --free F0,G --F0 0.1 --tau 1 \
  --R 10 --aT 2 --output "$flat" 2>"$dir/flat_np$np.err" || code=$?
[[ "$code" == 2 ]] || fail "np=$np: undetermined F0, G: exit $code, not 2: $(cat "$dir/flat_np$np.err")"
[[ ! -e "$flat" ]] || fail "np=$np: undetermined F0, G: $flat written"
grep -q "^mdrmap fit: error: --free: the records do not determine F0, G" "$dir/flat_np$np.err" ||
  fail "np=$np: undetermined F0, G: $(cat "$dir/flat_np$np.err")"
echo "PASS: np=$np fit $(grep -E '"(evaluations|wall_seconds)"' "$out" | tr -d '\n ')"
