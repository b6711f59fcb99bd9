#!/usr/bin/env bash
# examples.sh ... : every example study of jobs/examples runs at np = 1, 2
# and 4 to maps that are valid, complete, with every case done (none failed)
# and identical bit for bit.
source "$(dirname "$0")/common.sh"
dir="$WORKDIR/examples"
mkdir -p "$dir"
for config in "$SRCDIR"/jobs/examples/*.ini; do
  name=$(basename "$config" .ini)
  for np in 1 2 4; do
    out="$dir/${name}_np$np.h5"
    rm -f "$out"
    study "$np" --config "$config" --output "$out"
    "${CHECK[@]}" --complete --expect-failed 0 "$out" >/dev/null
    [[ $np == 1 ]] || "${COMPARE[@]}" "$dir/${name}_np1.h5" "$out" >/dev/null ||
      fail "$name: the map at np = $np differs from np = 1"
  done
  echo "PASS: $name at np = 1, 2, 4: identical maps"
done
