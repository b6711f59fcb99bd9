#!/usr/bin/env bash
# kill_resume.sh ... NP CONFIG REFERENCE SEED: SIGKILLs a study at a random
# moment, checks the half-written map (opens, valid layout, finished rows equal
# the reference), resumes it and checks the result equals the reference.
source "$(dirname "$0")/common.sh"
np=$1 config=$2 ref=$3 seed=$4
out="$WORKDIR/killed_np${np}_$seed.h5"
rm -f "$out" "$out".tmp-*
RANDOM=$seed
delay=$(printf '0.%03d' $((200 + RANDOM % 700)))
setsid "$MPIEXEC" -np "$np" "$MDRMAP" study --quiet --config "$config" --output "$out" &
pid=$!
sleep "$delay"
kill -KILL -- -"$pid" 2>/dev/null || true
wait "$pid" 2>/dev/null || true
sleep 0.2
pkill -KILL -f "$out" 2>/dev/null || true
echo "killed after ${delay}s"
if [[ -f "$out" ]]; then
  "${CHECK[@]}" "$out" || fail "map unreadable or invalid after kill -9"
  "${COMPARE[@]}" --done-only "$out" "$ref" || fail "finished rows differ from the reference"
  study "$np" --config "$config" --output "$out" --resume
else
  echo "killed before the map was created; starting afresh"
  study "$np" --config "$config" --output "$out"
fi
rm -f "$out".tmp-*
"${CHECK[@]}" --complete "$out"
"${COMPARE[@]}" "$out" "$ref" || fail "resumed map differs from an uninterrupted run"
echo "PASS: kill -9 after ${delay}s at np=$np, resumed"
