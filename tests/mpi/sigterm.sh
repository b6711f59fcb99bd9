#!/usr/bin/env bash
# sigterm.sh ... NP CONFIG REFERENCE: SIGTERM to every rank (what Slurm sends at
# the wall-time limit) must stop the study with exit code 3, a message saying
# how to resume, and a map that resumes to the reference.
source "$(dirname "$0")/common.sh"
np=$1 config=$2 ref=$3
out="$WORKDIR/sigterm_np$np.h5"
log="$WORKDIR/sigterm_np$np.log"
rm -f "$out"
"$MPIEXEC" -np "$np" "$MDRMAP" study --quiet --config "$config" --output "$out" 2>"$log" &
pid=$!
for _ in $(seq 100); do [[ -f "$out" ]] && break; sleep 0.05; done
sleep 0.3
pkill -TERM -P "$pid" || true # the ranks (children of mpirun), as Slurm signals the tasks
code=0
wait "$pid" || code=$?
cat "$log" >&2
[[ $code == 3 ]] || fail "exit code $code after SIGTERM, expected 3"
grep -q -- "--resume" "$log" || fail "no resume hint in the message"
"${CHECK[@]}" "$out"
"${COMPARE[@]}" --done-only "$out" "$ref"
study "$np" --config "$config" --output "$out" --resume
"${COMPARE[@]}" "$out" "$ref"
echo "PASS: SIGTERM at np=$np: exit 3, resumed to the reference"
