#!/usr/bin/env bash
# End-to-end test of the mdrmap-map/2 tools (python -m mdrmap map_healing,
# python -m mdrmap map_steps, python -m mdrmap map_rate_state, python -m mdrmap map_friction_velocity)
# on maps of the example studies made here.
#
#   bash tests/tools/test_map_tools.sh MDRMAP_EXE PYRUN SRCDIR WORKDIR
#
# Makes, with `mpirun -np 2 MDRMAP_EXE study --config jobs/examples/X.ini`
# (mpirun from PATH), in WORKDIR/map_tools_test: seed_step.h5 (depth control,
# one step, time series), velocity_steps.h5 (under load, up 10x and back),
# shs_holds.h5 (under load, holds 0.1 .. 1000 tau and a reslide), load_sweep.h5
# (3 loads x 25 velocities, a 10x step, no time series); a copy of
# shs_holds.h5 that says it is an mdrmap-map/1 map, a text file and an HDF5
# file that is not a map. Then checks:
#   - --help of each tool exits 0 with a usage line;
#   - every PNG has the PNG signature, an IHDR chunk, the figure's size;
#   - map_healing: the healing slope is positive at zeta0 = 1 (and at every
#     zeta0), and dmu_peak saturates for holds >> tau: after such a hold the
#     contact has crept into the Hertz contact (relaxation time tau), so the
#     holds of 316 and 1000 tau give the same dmu_peak to the solver's accuracy;
#   - map_steps: after the step up (event 0) every response has reached the
#     new stationary state (normalised response 1 at the end of 10 tau);
#     --select and --cases pick the cases they say;
#   - map_rate_state: over (v, F0) of load_sweep every a, b, a - b is defined
#     and the direct effect a > 0; over (v, w1_over_v) of seed_step the stop
#     (w1 = 0) gives 5 undefined cells of a per panel;
#   - map_friction_velocity: under load the maximum of the stationary friction,
#     interpolated from the map and from analytic/mu_pre at the map's
#     velocities, is within 2% of zeta0* = 1.39796 and mu* = 0.88627 a0/R
#     (docs/design.md, "Load control"); at fixed depth the tool says there is
#     no maximum;
#   - bad invocations (no file, not HDF5, not a map, an mdrmap-map/1 map, a map
#     of the wrong kind, an unknown axis, no time series, an event out of
#     range) exit 2 with exactly one line on stderr, no traceback, no PNG.
# Oversubscription and running as root are allowed here, for the test only.
set -euo pipefail

# shellcheck source=tests/tools/lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
tool_test_args map_tools_test "$@"
allow_mpi_here
HE=map_healing
ST=map_steps
RS=map_rate_state
FV=map_friction_velocity

# bad NAME EXPECTED CMD...: refuses (lib.sh), counted as a passed check
bad() {
  refuses "$@"
  ok "$1: exit 2: $(cat "$W/$1.err")"
}

cat >"$W/check_png.py" <<'EOF'
# pyrun-needs: struct
"""check_png.py FILE WIDTH HEIGHT: a PNG of WIDTH x HEIGHT pixels (+-5%), drawn."""
import os
import struct
import sys

path = sys.argv[1]
w0, h0 = int(sys.argv[2]), int(sys.argv[3])
with open(path, "rb") as f:
    head = f.read(33)
if len(head) < 33 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
    sys.exit(f"{path}: not a PNG (no signature and IHDR chunk)")
width, height = struct.unpack(">II", head[16:24])
if abs(width - w0) > 0.05 * w0 or abs(height - h0) > 0.05 * h0:
    sys.exit(f"{path}: {width} x {height} pixels, expected about {w0} x {h0}")
if os.path.getsize(path) < 20000:
    sys.exit(f"{path}: only {os.path.getsize(path)} bytes, too small for a drawn figure")
print(f"{os.path.basename(path)}: {width} x {height}")
EOF
png() {
  run "png_$(basename "$1" .png)" py "$W/check_png.py" "$@"
  ok "$(cat "$W/png_$(basename "$1" .png).out")"
}

# ---------------------------------------------------------------- the maps
for x in seed_step velocity_steps shs_holds load_sweep; do
  mpirun -np 2 "$MDRMAP" study --quiet --config "$SRCDIR/jobs/examples/$x.ini" \
    --output "$W/$x.h5" >"$W/study_$x.log" 2>&1 || {
    cat "$W/study_$x.log" >&2
    fail "mdrmap study --config jobs/examples/$x.ini"
  }
  run "check_$x" py "$SRCDIR/tools/maps/check_map.py" "$W/$x.h5" --complete
done
ok "made and checked seed_step.h5, velocity_steps.h5, shs_holds.h5, load_sweep.h5 (np = 2)"
cat >"$W/make_bad.py" <<'EOF'
# pyrun-needs: h5py numpy
"""make_bad.py MAP V1 OTHER: V1 a copy of MAP labelled mdrmap-map/1; OTHER not a map."""
import shutil
import sys

import h5py
import numpy as np

shutil.copy(sys.argv[1], sys.argv[2])
with h5py.File(sys.argv[2], "r+") as f:
    f.attrs["mdrmap_schema"] = np.bytes_("mdrmap-map/1")
with h5py.File(sys.argv[3], "w") as f:
    f["x"] = [1.0, 2.0]
EOF
run make_bad py "$W/make_bad.py" "$W/shs_holds.h5" "$W/v1.h5" "$W/other.h5"
echo "this is not an HDF5 file" >"$W/notes.h5"

for tool in "$HE" "$ST" "$RS" "$FV"; do
  t=$(basename "$tool" .py)
  run "help_$t" py "$tool" --help
  grep -q "^usage: " "$W/help_$t.out" || fail "$t --help: no usage line"
  expect_in "help_$t" "$W/help_$t.out" "python3 -m mdrmap $t"
done
ok "--help of the four tools: a usage line and an example"

# ---------------------------------------------------------------- map_healing
run healing py "$HE" "$W/shs_holds.h5" -o "$W/healing.png"
cat "$W/healing.out"
png "$W/healing.png" 1320 552
# the slope of each curve ("curve zeta0=Z: slope S a0/R per decade of hold")
awk '/^curve / { n++; z = $2; sub(/^zeta0=/, "", z); sub(/:$/, "", z); s = $4
       if (!(s + 0 > 0)) { print "slope " s " at zeta0 = " z " is not positive"; bad = 1 }
       if (z == "1") one = 1 }
     END { if (n != 3 || !one) { print n " curves, zeta0 = 1 among them: " one; bad = 1 }; exit bad }' \
  "$W/healing.out" || fail "healing: the slopes (see above)"
ok "map_healing: 3 curves (zeta0 = 0.1, 1, 10), each with a positive healing slope"
# saturation: the rows "T1/tau dmu_peak ..." of each curve; 316 and 1000 tau
awk '/^curve / { z = $2 }
     $1 ~ /^316/ { d3[z] = $2 }
     $1 ~ /^1000$/ { d4[z] = $2 }
     END { for (z in d4) { n++; diff = d4[z] - d3[z]; if (diff < 0) diff = -diff
             tol = 1e-3 * (d4[z] < 0 ? -d4[z] : d4[z]) + 1e-4
             printf "%s dmu_peak(316 tau) = %s, dmu_peak(1000 tau) = %s\n", z, d3[z], d4[z]
             if (!(d3[z] != "" && diff <= tol)) bad = 1 }
           exit (bad || n != 3) }' "$W/healing.out" >"$W/saturation.out" || {
  cat "$W/saturation.out" >&2
  fail "healing: dmu_peak does not saturate for holds >> tau"
}
ok "map_healing: dmu_peak(316 tau) = dmu_peak(1000 tau) to 1e-3 on every curve (saturated)"
run healing_select py "$HE" "$W/shs_holds.h5" --select v=0.09 -o "$W/healing_select.png"
expect_in healing_select "$W/healing_select.out" "--select v=0.09 -> v=0.1 (value 2 of 3): 9 case(s) left"
expect_in healing_select "$W/healing_select.out" "curve zeta0=1: slope"
ok "map_healing --select v=0.09: the 9 cases at v = 0.1 (zeta0 = 1)"

# ---------------------------------------------------------------- map_steps
run steps_up py "$ST" "$W/velocity_steps.h5" -o "$W/steps_up.png"
cat "$W/steps_up.out"
png "$W/steps_up.png" 1440 600
# rows: case zeta0 ratio mu_ss_before mu_ss_after mu_after norm0 norm_end D_c
awk '$1 ~ /^[0-9]+$/ && NF == 9 { n++; if ($3 != 10) bad = 1
       e = $8 - 1; if (e < 0) e = -e; if (!(e <= 0.02)) { print "case " $1 ": norm end " $8; bad = 1 } }
     END { exit (bad || n != 9) }' "$W/steps_up.out" || fail "map_steps: the step up has not settled"
ok "map_steps: 9 steps up by 10x, each at its new stationary state after 10 tau (normalised 1 +- 0.02)"
run steps_down py "$ST" "$W/velocity_steps.h5" --event 1 --select v=0.1 -o "$W/steps_down.png"
expect_in steps_down "$W/steps_down.out" "--select v=0.1 -> v=0.1 (value 5 of 9): 1 case(s) left"
expect_in steps_down "$W/steps_down.out" "event 1: 1 case(s)"
run steps_cases py "$ST" "$W/seed_step.h5" --cases 1,2,3 -o "$W/steps_cases.png"
expect_in steps_cases "$W/steps_cases.out" "event 0: 3 case(s); mu in units of a1/R"
ok "map_steps: --event 1 --select v=0.1 (one case), --cases 1,2,3 of a fixed-depth map"

# ---------------------------------------------------------------- map_rate_state
run rs_sweep py "$RS" "$W/load_sweep.h5" --x v --y F0 -o "$W/rs_sweep.png"
cat "$W/rs_sweep.out"
png "$W/rs_sweep.png" 1380 1032
expect_in rs_sweep "$W/rs_sweep.out" "event 0 over v (25 values, log) x F0 (3 values, log)"
awk '$1 == "a" || $1 == "b" || $1 == "a_minus_b" { n++; if ($3 != 75 || $4 != 0) bad = 1 }
     $1 == "a" && !($6 > 0) { print "a min " $6; bad = 1 }
     END { exit (bad || n != 3) }' "$W/rs_sweep.out" ||
  fail "map_rate_state: a, b, a-b not all defined over load_sweep, or a <= 0"
ok "map_rate_state: over (v, F0) every a, b, a - b is defined, and a > 0"
run rs_seed py "$RS" "$W/seed_step.h5" --x v --y w1_over_v --select tau=1.9 -o "$W/rs_seed.png"
expect_in rs_seed "$W/rs_seed.out" "--select tau=1.9 -> tau=2 (value 2 of 2)"
awk '$1 == "a" { exit !($4 == 5) }' "$W/rs_seed.out" || fail "map_rate_state: the stop is not undefined"
ok "map_rate_state: the stop (w1_over_v = 0) gives 5 undefined cells; --select says tau=2"
run rs_line py "$RS" "$W/velocity_steps.h5" --event 1 -o "$W/rs_line.png"
expect_in rs_line "$W/rs_line.out" "event 1 over v (9 values, log)"
ok "map_rate_state: one varying axis gives line plots (velocity_steps, event 1)"

# ---------------------------------------------------------------- map_friction_velocity
run fv py "$FV" "$W/load_sweep.h5" -o "$W/fv.png"
cat "$W/fv.out"
png "$W/fv.png" 960 648
# "maximum of F0=...: zeta0 = X (...), mu = Y (...); analytic: zeta0 = XA (...), mu = YA (...)"
awk -v zs=1.397964867 -v ms=0.886274212 '
  function rel(x, r) { x = x / r - 1; return x < 0 ? -x : x }
  /^maximum of / { n++
    for (i = 1; i <= NF; i++) { if ($i == "=") { v[++k] = $(i + 1) } }
    if (k != 4 * n || rel(v[k - 3], zs) > 0.02 || rel(v[k - 2], ms) > 0.02 ||
        rel(v[k - 1], zs) > 0.02 || rel(v[k], ms) > 0.02) { print "off: " $0; bad = 1 } }
  END { exit (bad || n != 3) }' "$W/fv.out" ||
  fail "map_friction_velocity: the maximum is not within 2% of zeta0* = 1.39796, mu* = 0.88627 a0/R"
ok "map_friction_velocity: the maxima of the 3 loads (map and closed form) are within 2% of zeta0*, mu*"
run fv_depth py "$FV" "$W/seed_step.h5" -o "$W/fv_depth.png"
expect_in fv_depth "$W/fv_depth.out" "no maximum"
ok "map_friction_velocity: at fixed depth mu rises monotonically (no maximum)"

# ---------------------------------------------------------------- bad input
for tool in "$HE" "$ST" "$RS" "$FV"; do
  t=$(basename "$tool" .py)
  bad "${t}_missing" "no such file" py "$tool" "$W/absent.h5"
  bad "${t}_not_hdf5" "is not a readable HDF5 file" py "$tool" "$W/notes.h5"
  bad "${t}_not_map" "is not an mdrmap map (no root attribute mdrmap_schema)" py "$tool" "$W/other.h5"
  bad "${t}_schema1" "is an mdrmap-map/1 map; this tool reads mdrmap-map/2 maps: rerun the study" \
    py "$tool" "$W/v1.h5"
done
bad healing_not_shs "is not a slide-hold-slide map" py "$HE" "$W/velocity_steps.h5"
bad healing_one_segment "is not a slide-hold-slide map" py "$HE" "$W/load_sweep.h5"
bad healing_select_axis "no grid axis 'speed'" py "$HE" "$W/shs_holds.h5" --select speed=1
bad steps_no_timeseries "has no /timeseries" py "$ST" "$W/load_sweep.h5"
bad steps_hold "starts a hold (w = 0) in every chosen case" py "$ST" "$W/shs_holds.h5"
bad steps_event "--event 2: the map has 2 event(s) (0..1)" py "$ST" "$W/velocity_steps.h5" --event 2
bad steps_case "--cases 99: the map has 9 cases" py "$ST" "$W/velocity_steps.h5" --cases 99
bad rs_axis "--x speed: not a grid axis" py "$RS" "$W/load_sweep.h5" --x speed
bad rs_unfixed "grid axis tau has 2 values" py "$RS" "$W/seed_step.h5" --x v --y w1_over_v
bad rs_select_value "--select tau=abc: 'abc' is not a number" py "$RS" "$W/seed_step.h5" --select tau=abc
bad fv_option "unrecognized arguments" py "$FV" "$W/load_sweep.h5" --bogus

echo "PASS: map tools ($checks checks)"
