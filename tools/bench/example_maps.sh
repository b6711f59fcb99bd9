#!/usr/bin/env bash
# The maps of the example studies (jobs/examples/*.ini) by two builds, case by
# case within each study's rtol (tools/maps/compare_within_rtol.py):
#
#   bash tools/bench/example_maps.sh OLD_MDRMAP NEW_MDRMAP [WORKDIR]
#
# Each study runs with --timeseries true at mpirun -np 1 under both builds; a
# study the old build refuses (a newer config) is reported as such. Prints one
# line per study; exit 1 when a study's maps differ by more than its rtol.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
OLD=${1:?usage: example_maps.sh OLD_MDRMAP NEW_MDRMAP [WORKDIR]}
NEW=${2:?usage: example_maps.sh OLD_MDRMAP NEW_MDRMAP [WORKDIR]}
WORK=${3:-$(mktemp -d)}
mkdir -p "$WORK"
OLD=$(realpath "$OLD") NEW=$(realpath "$NEW") WORK=$(realpath "$WORK")
if [[ "$(id -u)" == 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
status=0
for ini in "$ROOT"/jobs/examples/*.ini; do
  name=$(basename "$ini" .ini)
  rtol=$(sed -n 's/^rtol *= *\([0-9.eE+-]*\).*/\1/p' "$ini" | head -n 1)
  run() { # run EXE MAP: the study, at np 1, from the examples' directory
    (cd "$ROOT/jobs/examples" && mpirun -q -np 1 "$1" study --config "$ini" --output "$2" \
      --overwrite --quiet --timeseries true) >"$2.log" 2>&1
  }
  if ! run "$OLD" "$WORK/$name.old.h5"; then
    echo "$name: the old build refuses or fails it: $(tail -n 1 "$WORK/$name.old.h5.log")"
    continue
  fi
  run "$NEW" "$WORK/$name.new.h5" || { echo "$name: FAILED with the new build"; status=1; continue; }
  printf '%s (rtol %s): ' "$name" "$rtol"
  /usr/bin/python3 "$ROOT/tools/maps/compare_within_rtol.py" "$WORK/$name.old.h5" \
    "$WORK/$name.new.h5" --rtol "$rtol" || status=1
done
exit $status
