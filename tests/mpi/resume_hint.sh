#!/usr/bin/env bash
# resume_hint.sh ... NP CONFIG: a study run with overrides (--set and an
# override option) and interrupted by SIGTERM prints "resume with: COMMAND";
# that command, run as printed (mpirun and mdrmap replaced by the test's),
# resumes the map to completion instead of being refused for a different
# study (issue 32: the hint dropped the overrides). Waits for conditions.
source "$(dirname "$0")/common.sh"
np=$1 config=$2
out="$WORKDIR/resume_hint_np$np.h5"
log="$WORKDIR/resume_hint_np$np.log"
rm -f "$out"
overrides=(--set 'grid.tau=linspace:0.5:2.5:10' --samples 51 --set 'run.rtol= 1e-3')
"$MPIEXEC" -np "$np" "$MDRMAP" study --quiet --config "$config" --output "$out" \
  "${overrides[@]}" 2>"$log" &
pid=$!
ranks() { pgrep -P "$pid" || true; }
cpu_ticks() { # CPU ticks the ranks used (utime + stime)
  local total=0 r t
  for r in $(ranks); do
    t=$(awk '{ print $14 + $15 }' "/proc/$r/stat" 2>/dev/null || echo 0)
    total=$((total + t))
  done
  echo "$total"
}
for _ in $(seq 1200); do [[ -f "$out" ]] && break; sleep 0.05; done
[[ -f "$out" ]] || fail "the map was not created within 60 s"
# cases are running (one CPU second past the map's creation)
start=$(cpu_ticks)
for _ in $(seq 1200); do (($(cpu_ticks) >= start + $(getconf CLK_TCK))) && break; sleep 0.05; done
kill -0 "$pid" 2>/dev/null || fail "the study ended before the signal: $(cat "$log")"
for r in $(ranks); do kill -TERM "$r"; done
code=0
wait "$pid" || code=$?
cat "$log" >&2
[[ $code == 3 ]] || fail "exit code $code after SIGTERM, expected 3"
hint=$(sed -n 's/.*resume with: //p' "$log")
[[ -n $hint ]] || fail "no 'resume with:' command in the message"
prefix="mpirun -np $np mdrmap "
[[ $hint == "$prefix"* ]] || fail "the resume command does not start with '$prefix': $hint"
args=()
eval "args=(${hint#"$prefix"})" # the words as a shell reads them (quoted by mdrmap)
"$MPIEXEC" -np "$np" "$MDRMAP" "${args[@]}" ||
  fail "the printed resume command failed: $hint"
"${CHECK[@]}" --quiet --complete "$out"
echo "PASS: the printed resume command resumed the study with its overrides: $hint"
