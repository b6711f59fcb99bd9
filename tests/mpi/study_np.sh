#!/usr/bin/env bash
# study_np.sh ... NP CONFIG: runs the study at NP ranks; the map must be valid,
# complete and, for NP > 1, identical bit for bit to the NP = 1 map.
source "$(dirname "$0")/common.sh"
np=$1 config=$2
name=$(basename "$config" .ini)
out="$WORKDIR/${name}_np$np.h5"
rm -f "$out"
study "$np" --config "$config" --output "$out"
"${CHECK[@]}" --complete "$out"
if [[ "$np" != 1 ]]; then
  "${COMPARE[@]}" "$WORKDIR/${name}_np1.h5" "$out"
fi
echo "PASS: np=$np $name"
