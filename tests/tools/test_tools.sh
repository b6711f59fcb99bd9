#!/usr/bin/env bash
# End-to-end test of the post-processing tools (python -m mdrmap plot_timeseries,
# python -m mdrmap plot_map, python -m mdrmap map_summary) on small maps made here.
#
#   bash tests/tools/test_tools.sh MDRMAP_EXE PYRUN SRCDIR WORKDIR
#
# The maps are mdrmap-map/2 maps (docs/reference/map-schema.md) made from configs in the
# seed's one-step syntax (v1_over_v in [grid], t_end_over_tau in [run]: the
# history axis w1_over_v and T1_over_tau); the checks name their datasets
# (mu_after_0, analytic/mu_ss_0, ...) and accept either name of the step's axis.
# Makes, with `mpirun -np 2 MDRMAP_EXE study` (mpirun from PATH), in WORKDIR/tools_test:
#   grid.h5       a 3 x 1 x 2 x 3 x 2 grid (d, R, tau with tau = 0, v, v1_over_v; G and
#                 t_end_over_tau are axes of length 1 between them) with time series
#   grid_nots.h5  the same grid without time series
#   cases.h5      a [cases] map (no /grid) with time series, with v1 = 0 and tau = 0 cases
#   failing.h5    a [cases] map with one failed case (the baseline solver refuses it)
#   partial.h5    grid.h5 as a killed study leaves it (9 cases pending, 1 failed)
# and a non-HDF5 file and an HDF5 file that is not an mdrmap map. Then runs
# every tool on them (TOOLS_TEST_JOBS at a time, default 2) and checks:
#   - --help of each tool exits 0 and prints a usage line;
#   - every PNG starts with the PNG signature and an IHDR chunk, has a
#     plausible width and height (read with struct from IHDR) and a size that
#     a drawn plot has;
#   - the tools say which case --select picked, which slice values they took
#     and how many not-done (failed or pending) cases they skipped;
#   - map_summary prints the counts, the grid axes and the failed cases'
#     messages; its CSV has a header (case, parameters, status, results,
#     analytic_*, residual_*, message) and one row per case, and --where
#     status=1 keeps the done rows only;
#   - bad invocations (missing file, not HDF5, not an mdrmap map, no time
#     series, unknown quantity, bad slice value or axis, case out of range, bad
#     --where, unknown option) exit 2 with exactly one line on stderr and no
#     traceback, and write no PNG.
# Oversubscription and running as root are allowed here, for the test only.
set -euo pipefail

# shellcheck source=tests/tools/lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
tool_test_args tools_test "$@"
allow_mpi_here
TS=plot_timeseries
PM=plot_map
MS=map_summary
JOBS=${TOOLS_TEST_JOBS:-2}
started=()
bad_names=()

# bad NAME EXPECTED CMD...: must exit 2 with exactly one stderr line containing EXPECTED
bad() {
  local name=$1 expected=$2 rc=0 lines
  shift 2
  "$@" >"$W/$name.out" 2>"$W/$name.err" || rc=$?
  lines=$(wc -l <"$W/$name.err")
  if ((rc != 2)) || ((lines != 1)) || ! grep -qF -- "$expected" "$W/$name.err"; then
    echo "--- $name stderr:" >&2
    cat "$W/$name.err" >&2
    fail "$name: expected exit 2 and one stderr line with '$expected', got exit $rc and $lines lines"
  fi
}

# bg run|bad NAME ...: the same, in the background, at most $JOBS at a time; join waits
bg() {
  local kind=$1 name=$2
  shift 2
  while (($(jobs -rp | wc -l) >= JOBS)); do
    wait -n || true
  done
  ("$kind" "$name" "$@" && : >"$W/$name.passed") &
  started+=("$name")
  [[ "$kind" != bad ]] || bad_names+=("$name")
}
join() {
  wait
  local name
  for name in "${started[@]}"; do
    [[ -e "$W/$name.passed" ]] || fail "$name failed (see above)"
  done
  started=()
}

study() {
  mpirun -np 2 "$MDRMAP" study --quiet "$@" >"$W/study.log" 2>&1 || {
    cat "$W/study.log" >&2
    fail "mdrmap study $*"
  }
}

# ---------------------------------------------------------------- the maps
cat >"$W/grid.ini" <<'EOF'
; 3 x 1 x 2 x 3 x 2 = 36 cases, with time series; tau = 0 is the elastic limit
[grid]
d         = logspace:1e-4:1e-2:3
R         = 1
tau       = 0, 1
v         = logspace:1e-1:1e3:3
v1_over_v = 1e-4, 0.1
[run]
samples    = 21
timeseries = true
EOF
cat >"$W/cases.csv" <<'EOF'
d,R,tau,v,v1
1e-3,1,1,10,0
1e-3,1,1,10,0.1
1e-2,2,0.5,100,1
1e-3,1,0,1,0.5
EOF
cat >"$W/cases.ini" <<'EOF'
[cases]
file = cases.csv
[run]
samples    = 21
timeseries = true
EOF
cat >"$W/failing.csv" <<'EOF'
d,R,tau,v,v1
1e-3,1,1,0.03,0.003
1e-3,1,1,3e6,3e5
1e-3,1,1,0.01,0.02
EOF
cat >"$W/failing.ini" <<'EOF'
; the fixed-step baseline cannot afford the second case (v tau/a1 ~ 1e8): it is marked failed
[cases]
file = failing.csv
[run]
solver     = baseline
rtol       = 0.05
samples    = 11
timeseries = true
EOF
cat >"$W/make_other.py" <<'EOF'
# pyrun-needs: h5py
import sys
import h5py
with h5py.File(sys.argv[1], "w") as f:
    f["x"] = [1.0, 2.0]
EOF
cat >"$W/make_partial.py" <<'EOF'
# pyrun-needs: h5py numpy
"""A copy of a map as a killed study leaves it: every 4th case pending, case 1 failed
(mdrmap-map/2: its message in /failures)."""
import shutil
import sys
import h5py
import numpy as np
shutil.copy(sys.argv[1], sys.argv[2])
with h5py.File(sys.argv[2], "r+") as f:
    status = f["results/status"][()]
    status[::4] = 0
    status[1] = -1
    f["results/status"][...] = status
    for name in ("failures/case", "failures/message"):
        if name in f:
            del f[name]
    f.create_dataset("failures/case", data=np.array([1], dtype=np.uint64))
    f.create_dataset("failures/message", data=np.array([b"injected failure"]))
EOF
study --config "$W/grid.ini" --output "$W/grid.h5"
study --config "$W/grid.ini" --output "$W/grid_nots.h5" --timeseries false
study --config "$W/cases.ini" --output "$W/cases.h5"
study --config "$W/failing.ini" --output "$W/failing.h5"
echo "this is not an HDF5 file" >"$W/notes.h5"
py "$W/make_other.py" "$W/other.h5"
py "$W/make_partial.py" "$W/grid.h5" "$W/partial.h5"
ok "made grid.h5, grid_nots.h5, cases.h5, failing.h5, partial.h5, notes.h5, other.h5"

# ---------------------------------------------------------------- every tool run
for tool in "$TS" "$PM" "$MS"; do
  bg run "help_$(basename "$tool" .py)" py "$tool" --help
done
# plot_timeseries
bg run ts_default py "$TS" "$W/grid.h5" -o "$W/ts_default.png"
bg run ts_select py "$TS" "$W/grid.h5" --case 0 --select d=1e-2,tau=1,v=1e3,v1_over_v=1e-4 --scaled \
  -o "$W/ts_select.png"
bg run ts_cases py "$TS" "$W/cases.h5" --case all -o "$W/ts_cases.png"
bg run ts_failing py "$TS" "$W/failing.h5" --case all -o "$W/ts_failing.png"
bg run ts_partial py "$TS" "$W/partial.h5" --case all --zoom -o "$W/ts_partial.png"
# plot_map
bg run pm_default py "$PM" "$W/grid.h5" -o "$W/pm_default.png"
bg run pm_partial py "$PM" "$W/partial.h5" -o "$W/pm_partial.png"
bg run pm_slices py "$PM" "$W/grid.h5" mu_end_0 residuals/mu_jump analytic/mu_ss_0 --x v --y d \
  --slice tau=0.9 --slice v1_over_v=0.2 --log-color --zeta-lines --contour 0.01 -o "$W/pm_slices.png"
bg run pm_similarity py "$PM" "$W/grid_nots.h5" mu_jump --similarity -o "$W/pm_similarity.png"
bg run pm_cases py "$PM" "$W/cases.h5" FN_jump -o "$W/pm_cases.png"
bg run pm_failing py "$PM" "$W/failing.h5" --x v --y w1 -o "$W/pm_failing.png"
# map_summary
bg run ms_grid py "$MS" "$W/grid.h5"
bg run ms_partial py "$MS" "$W/partial.h5" --no-config
bg run ms_failing py "$MS" "$W/failing.h5" --csv "$W/failing.csv.out" --top 3
bg run ms_cases py "$MS" "$W/cases.h5" --csv "$W/cases.csv.out" -o "$W/cases_summary.txt"
bg run ms_where py "$MS" "$W/failing.h5" --where status=1 --csv "$W/done.csv.out" --no-config
# user errors: exit 2, one line on stderr
for tool in "$TS" "$PM" "$MS"; do
  t=$(basename "$tool" .py)
  bg bad "${t}_missing" "no such file" py "$tool" "$W/absent.h5" -o "$W/x.png"
  bg bad "${t}_not_hdf5" "is not a readable HDF5 file" py "$tool" "$W/notes.h5" -o "$W/x.png"
  bg bad "${t}_not_map" "is not an mdrmap map (no root attribute mdrmap_schema)" py "$tool" \
    "$W/other.h5" -o "$W/x.png"
done
bg bad ts_no_timeseries "rerun the study with \`--timeseries true\`" py "$TS" "$W/grid_nots.h5" \
  -o "$W/x.png"
bg bad ts_case_range "the map has 36 cases (0..35)" py "$TS" "$W/grid.h5" --case 99 -o "$W/x.png"
bg bad ts_select_name "unknown parameter 'speed'" py "$TS" "$W/grid.h5" --select speed=1 -o "$W/x.png"
bg bad pm_unknown "unknown quantity 'mu_jmp'; valid: D_c_0, FN_after_0" py "$PM" "$W/grid.h5" mu_jmp -o "$W/x.png"
bg bad pm_slice_value "--slice tau=abc: 'abc' is not a number" py "$PM" "$W/grid.h5" --slice tau=abc \
  -o "$W/x.png"
bg bad pm_slice_axis "no grid axis 'foo'" py "$PM" "$W/grid.h5" --slice foo=1 -o "$W/x.png"
bg bad pm_x_axis "not a grid axis" py "$PM" "$W/grid.h5" --x speed -o "$W/x.png"
bg bad ms_where_bad "no column 'foo'" py "$MS" "$W/grid.h5" --where foo=1
bg bad ms_option "unrecognized arguments" py "$MS" "$W/grid.h5" --bogus
n_runs=${#started[@]}
join
ok "$n_runs tool runs exited as expected ($JOBS at a time)"

# ---------------------------------------------------------------- --help
for t in plot_timeseries plot_map map_summary; do
  expect_in "help_$t" "$W/help_$t.out" "usage:"
done
ok "--help of the three tools exits 0 with a usage line"

# ---------------------------------------------------------------- what the plot tools said
expect_in ts_default "$W/ts_default.out" "wrote"
expect_in ts_select "$W/ts_select.out" "--select d=1e-2,tau=1,v=1e3,v1_over_v=1e-4 -> case 34"
expect_in ts_select "$W/ts_select.out" "(2 cases)"
expect_in ts_cases "$W/ts_cases.out" "(4 cases)"
expect_in ts_failing "$W/ts_failing.out" "skipped 1 case not done: 1 (failed)"
expect_in ts_failing "$W/ts_failing.out" "(2 cases)"
expect_in ts_partial "$W/ts_partial.out" "skipped 10 cases not done: 0 (pending), 1 (failed), 4 (pending)"
expect_in ts_partial "$W/ts_partial.out" "(26 cases)"
ok "plot_timeseries: default case, --case/--select/--scaled, a [cases] map, failed and pending cases skipped"

expect_in pm_default "$W/pm_default.out" "axis tau not sliced: taking tau=0"
expect_in pm_partial "$W/pm_partial.out" "skipped 6 of 9 cases in the plot: not done (0 failed, 6 pending)"
expect_in pm_slices "$W/pm_slices.out" "slice tau=0.9 -> tau=1"
expect_in pm_slices "$W/pm_slices.out" "slice v1_over_v=0.2 -> "
grep -qE "slice v1_over_v=0.2 -> [vw]1_over_v=0.1 " "$W/pm_slices.out" || fail "pm_slices: v1_over_v"
expect_in pm_failing "$W/pm_failing.out" "skipped 1 of 3 cases"
ok "plot_map: default axes and slices, pending cells, --slice/--log-color/--zeta-lines/--contour with 3" \
  "panels, --similarity, [cases] scatter, a failed case"

# ---------------------------------------------------------------- the PNGs
cat >"$W/check_png.py" <<'EOF'
# pyrun-needs: struct
"""check_png.py FILE W_MIN W_MAX H_MIN H_MAX: a PNG of plausible size."""
import os
import struct
import sys

path = sys.argv[1]
wmin, wmax, hmin, hmax = (int(a) for a in sys.argv[2:6])
with open(path, "rb") as f:
    head = f.read(33)
size = os.path.getsize(path)
if len(head) < 33 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
    sys.exit(f"{path}: not a PNG (no signature and IHDR chunk)")
width, height = struct.unpack(">II", head[16:24])
if not (wmin <= width <= wmax and hmin <= height <= hmax):
    sys.exit(f"{path}: {width} x {height} pixels, expected {wmin}..{wmax} x {hmin}..{hmax}")
if size < 10000:
    sys.exit(f"{path}: only {size} bytes, too small for a drawn plot")
print(f"{os.path.basename(path)}: {width} x {height}, {size} bytes")
EOF
# plot_timeseries: 12 x 8.4 in at 120 dpi; plot_map: 5.9 in wide per panel
for f in ts_default ts_select ts_cases ts_failing ts_partial; do
  bg run "png_$f" py "$W/check_png.py" "$W/$f.png" 1400 1500 950 1050
done
for f in pm_default pm_partial pm_similarity pm_cases pm_failing; do
  bg run "png_$f" py "$W/check_png.py" "$W/$f.png" 650 760 600 700
done
bg run png_pm_slices py "$W/check_png.py" "$W/pm_slices.png" 2050 2200 600 700
join
[[ ! -e "$W/x.png" ]] || fail "a failed invocation wrote $W/x.png"
ok "11 PNGs: signature, IHDR chunk, width x height, size"

# ---------------------------------------------------------------- summary and CSV
for s in "cases: 36  done 36, failed 0, pending 0" "numerical error" "distance from a state or a limit" \
  "mdrmap-map/2" "config text:" "MPI size      2" "samples 21 per segment" "segments      1;" \
  "loading       depth" "zeta = v tau / a1"; do
  expect_in ms_grid "$W/ms_grid.out" "$s"
done
# the grid: d, R, tau, v and the step's axis (T1_over_tau may be listed too)
for re in "^grid: 7 axes, shape 3 x 1 x 2 x 1 x 3 x 2 x 1 " "^  d +3 values \(log\): 1e-4, 0.001, 0.01$" \
  "^  tau +2 values: 0, 1$" "^  [vw]1_over_v +2 values: 1e-4, 0.1$"; do
  grep -qE -- "$re" "$W/ms_grid.out" || { cat "$W/ms_grid.out" >&2; fail "ms_grid: no line /$re/"; }
done
expect_in ms_partial "$W/ms_partial.out" "cases: 36  done 26, failed 1, pending 9"
grep -qE "^  case 1: .*d=1e-4 .*v=0.1 w1=0.01 T1=.*: injected failure$" "$W/ms_partial.out" ||
  fail "ms_partial: case 1's parameters and message"
for s in "cases: 3  done 2, failed 1, pending 0" "case list (no /grid): 3 cases" "failed cases (1):" \
  "top 3 by |value|:"; do
  expect_in ms_failing "$W/ms_failing.out" "$s"
done
grep -qE "^  case 1: .*d=0.001 .*v=3e6 w1=3e5 T1=.*: baseline:" "$W/ms_failing.out" ||
  fail "ms_failing: case 1's parameters and message"
expect_in ms_cases "$W/cases_summary.txt" "case list (no /grid): 4 cases"
expect_in ms_where "$W/ms_where.out" "filter: status=1 keeps 2 of 3 cases"
cat >"$W/check_csv.py" <<'EOF'
# pyrun-needs: csv
"""check_csv.py FILE ROWS [STATUS...]: header and row count of a map_summary CSV."""
import csv
import sys

path, rows = sys.argv[1], int(sys.argv[2])
with open(path, newline="") as f:
    table = list(csv.reader(f))
head = table[0]
# mdrmap-map/2: case, the /cases columns (d R tau G v, in the map's order), w1 T1, zeta, status
params = ["d", "R", "tau", "G", "v"]
start = head[: len(params) + 1]
if start[0] != "case" or sorted(start[1:]) != sorted(params) or \
        head[len(start): len(start) + 4] != ["w1", "T1", "zeta", "status"] or head[-1] != "message":
    sys.exit(f"{path}: header {head[:12]} ... {head[-1]}")
for col in ["FN_pre", "mu_pre", "mu_after_0", "mu_peak_0", "a_0", "D_c_0", "error_estimate",
            "analytic_mu_jump", "analytic_mu_ss_0", "residual_mu_jump", "residual_mu_end_0"]:
    if col not in head:
        sys.exit(f"{path}: no column {col}")
if len(table) - 1 != rows:
    sys.exit(f"{path}: {len(table) - 1} rows, expected {rows}")
if any(len(r) != len(head) for r in table):
    sys.exit(f"{path}: ragged rows")
status = [r[head.index("status")] for r in table[1:]]
if len(sys.argv) > 3 and status != sys.argv[3:]:
    sys.exit(f"{path}: status column {status}, expected {sys.argv[3:]}")
print(f"{path}: {len(head)} columns, {rows} rows, status {' '.join(status)}")
EOF
run csv_failing py "$W/check_csv.py" "$W/failing.csv.out" 3 1 -1 1
expect_in csv_failing "$W/failing.csv.out" "too expensive"
run csv_cases py "$W/check_csv.py" "$W/cases.csv.out" 4 1 1 1 1
run csv_where py "$W/check_csv.py" "$W/done.csv.out" 2 1 1
ok "map_summary: provenance, counts, axes, failed messages; CSV header and rows; --where status=1"

# ---------------------------------------------------------------- user errors
for name in "${bad_names[@]}"; do
  ok "$name: exit 2: $(cat "$W/$name.err")"
done

echo "PASS: post-processing tools ($checks checks)"
