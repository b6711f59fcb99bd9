#!/usr/bin/env bash
# failing.sh ... NP CONFIG: a case whose solver throws is marked failed
# (status -1, message kept) and the study completes the others, exit 0.
source "$(dirname "$0")/common.sh"
np=$1 config=$2
out="$WORKDIR/failing_np$np.h5"
rm -f "$out"
study "$np" --config "$config" --output "$out"
"${CHECK[@]}" --complete --expect-failed 1 "$out"
echo "PASS: a failing case is recorded and the study completes"
