#!/usr/bin/env bash
# Sets up, builds mdrmap (the program and the Python module, whose import it
# checks) and runs the main job on the built-in example study: a
# slide-hold-slide study under load (jobs/examples/shs_holds.ini) on all local
# cores, written to out/shs_holds.h5, and its healing curve
# (out/healing.png); then the seed's friction map and single cases as CSV.
#
#   bash tools/quickstart.sh
#
# Environment: as tools/build.sh (BUILD_DIR, BUILD_TYPE, JOBS), and
#   OUT_DIR=out   where the example output goes (relative to the repository root)
#   MDRMAP_PYTHON=ON  builds the Python module too (target mdrmap_python: needs
#                 pybind11-dev python3-dev python3-numpy) and checks that
#                 `import mdrmap` works with PYTHONPATH=BUILD_DIR/python;
#                 OFF: the program only
# To add an example: add a line to the "Examples" section at the bottom.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"

BUILD_DIR=${BUILD_DIR:-build}
OUT_DIR=${OUT_DIR:-out}
export BUILD_DIR

bash tools/setup.sh
if [[ "${MDRMAP_PYTHON:-ON}" == OFF ]]; then
  BUILD_TARGETS=${BUILD_TARGETS:-mdrmap} bash tools/build.sh -DMDRMAP_PYTHON=OFF
else
  BUILD_TARGETS=${BUILD_TARGETS:-mdrmap mdrmap_python} bash tools/build.sh -DMDRMAP_PYTHON=ON
fi

MDRMAP="$BUILD_DIR/src/mdrmap"
[[ -x "$MDRMAP" ]] || { echo "quickstart: $MDRMAP was not built" >&2; exit 1; }

# The Python module, imported as a user would: PYTHONPATH=BUILD_DIR/python,
# with the interpreter it was built for.
if [[ "${MDRMAP_PYTHON:-ON}" != OFF ]]; then
  # (FindPython's cache entry; Python_EXECUTABLE itself when given with -D)
  python=$(sed -n 's/^_\{0,1\}Python_EXECUTABLE:[A-Z]*=//p' "$BUILD_DIR/CMakeCache.txt" | tail -n 1)
  pythonpath=$(cd "$BUILD_DIR" && pwd)/python
  echo
  echo "== PYTHONPATH=$pythonpath ${python:-python3} -c 'import mdrmap'"
  PYTHONPATH="$pythonpath${PYTHONPATH:+:$PYTHONPATH}" "${python:-python3}" -c \
    'import mdrmap; print("mdrmap", mdrmap.__version__, "from", mdrmap.__file__)' || {
    echo "quickstart: import mdrmap failed (the build's module: $pythonpath/mdrmap)" >&2
    exit 1
  }
fi
mkdir -p "$OUT_DIR"

# simulate NAME ARGS...: runs `mdrmap simulate ARGS --output OUT_DIR/NAME.csv`
# and shows the start and the end of the file.
simulate() {
  local name=$1
  shift
  local csv="$OUT_DIR/$name.csv"
  echo
  echo "== $name: mdrmap simulate $* --output $csv"
  rm -f "$csv"
  "$MDRMAP" simulate "$@" --output "$csv"
  if [[ ! -s "$csv" ]] || ! grep -q '^t,segment,FN,Fx,mu,a2$' "$csv"; then
    echo "quickstart: mdrmap simulate wrote no CSV with header t,segment,FN,Fx,mu,a2 to $csv" >&2
    exit 1
  fi
  local header_line
  header_line=$(grep -n -m1 '^t,segment,FN,Fx,mu,a2$' "$csv" | cut -d: -f1)
  head -n "$((header_line + 4))" "$csv"
  echo "..."
  tail -n 1 "$csv"
  echo "($(($(wc -l <"$csv") - header_line)) samples in $csv)"
}

# study NAME CONFIG: the parallel study on every local core (mpirun), map in
# OUT_DIR/NAME.h5 (replaced if it is an mdrmap map from an earlier run).
study() {
  local name=$1 config=$2
  local map="$OUT_DIR/$name.h5" np
  np=$(nproc 2>/dev/null || echo 1)
  echo
  echo "== $name: mpirun -np $np mdrmap study --config $config --output $map --overwrite"
  # Open MPI refuses to run as root unless told; only this local demo says so.
  if [[ "$(id -u)" == 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
  local args=(study --config "$config" --output "$map")
  [[ -f "$map" ]] && args+=(--overwrite)
  mpirun -np "$np" "$MDRMAP" "${args[@]}"
  if command -v h5ls >/dev/null; then h5ls "$map"; fi
  tools/pyrun tools/maps/check_map.py --complete "$map" || true
}

# --- Examples ---------------------------------------------------------------
# The main job: slide-hold-slide under a constant normal load (27 cases: holds
# of 0.1 to 1000 tau at zeta0 = v tau / a0 = 0.1, 1, 10), and its healing
# curve: the friction peak after the reslide grows with the hold time and
# saturates after about 10 tau (0.196 a0/R at zeta0 = 1).
study shs_holds jobs/examples/shs_holds.ini
echo
echo "== healing curve: tools/pyrun -m mdrmap map_healing $OUT_DIR/shs_holds.h5 -o $OUT_DIR/healing.png"
tools/pyrun -m mdrmap map_healing "$OUT_DIR/shs_holds.h5" -o "$OUT_DIR/healing.png"

# The seed's experiment as a map: friction coefficient over sliding velocity
# and depth, before and after a drop to v1 = 0.01 v (561 cases).
study friction_map jobs/examples/friction_map.ini

# The seed paper's start-stop test: a fast slide, v tau / sqrt(R d) = 1e3
# (a2 ~ 0, mu = 0.133 ~ 4/3 sqrt(d/R)), drops to v1 = 1e-4 v, v1 tau / sqrt(R d)
# = 0.1. At t = 0+ F_N drops from 4.00 to 0.0031 and mu to 0.083 (3/4 sqrt(d/R)
# = 0.075 in the limit v1 -> 0); then a2 grows from 5e-4 a1 towards
# a2(v1) = 0.905 a1 (a1 = 0.1) and mu relaxes towards 0.0185.
simulate start_stop --d 1e-2 --R 1 --tau 1 --v 100 --v1 1e-2 --G 1

# A velocity-step sequence (zeta0 = v tau / sqrt(R d) = 1): up tenfold, back
# down, down tenfold again, a hold of 10 tau, and a restart. The '# event'
# lines give per change mu before and after it, its extremum, D_c and the
# apparent rate-and-state parameters a, a - b, b.
simulate step_sequence --d 1e-2 --R 1 --tau 1 --v 0.1 \
  --history 1:4,0.1:4,0.01:6,0:10,0.1:4 --samples 41

echo
echo "quickstart: done; output in $OUT_DIR/"
