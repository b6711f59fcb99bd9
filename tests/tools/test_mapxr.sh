#!/usr/bin/env bash
# Test of the map's self-description through xarray (python -m mdrmap mapxr): maps made
# here with `mpirun -np 2 mdrmap study` open with xarray.open_dataset(engine=
# "h5netcdf", group=...) with named dimensions (case, event, sample) and the grid's
# axes as coordinates of /grid; mapxr.open_map merges the groups with the
# /schema units; to_grid turns a 5-axis grid (d, R, tau, v, v1_over_v:
# 2 x 2 x 2 x 3 x 2 = 48 cases) into a 5-dimensional Dataset whose coordinates
# are the axis values and whose values are the 1-D rows, the axes of one
# value (G, t_end_over_tau) scalar coordinates (the maps are
# mdrmap-map/2 maps: the step's axis is w1_over_v, or v1_over_v as the config
# names it, and T1_over_tau may be a further axis of length 1; undefined
# event metrics are NaN). A copy of the map
# without /schema and dimension scales (as older maps are) still opens with
# mapxr; the tools (map_summary) refuse it, and a copy without /scales, with
# one line naming the missing group. Every group of a map, /failures (with
# and without failed cases), /provenance and /scales included, opens with
# plain xarray without phony dimensions. One-line errors.
#
#   bash tests/tools/test_mapxr.sh MDRMAP_EXE PYRUN SRCDIR WORKDIR
set -euo pipefail

# shellcheck source=tests/tools/lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
tool_test_args mapxr_test "$@"
allow_mpi_here
XR=mapxr
MS=map_summary

study() {
  mpirun -np 2 "$MDRMAP" study --quiet "$@" >"$W/study.log" 2>&1 || {
    cat "$W/study.log" >&2
    fail "mdrmap study $*"
  }
}

cat >"$W/grid5.ini" <<'EOF'
; 2 x 2 x 2 x 3 x 2 = 48 cases, with time series
[grid]
d         = 1e-3, 1e-2
R         = 1, 2
tau       = 0.5, 2
v         = 0.1, 1, 10
v1_over_v = 1e-3, 0.5
[run]
samples    = 7
timeseries = true
EOF
cat >"$W/cases.csv" <<'EOF'
d,R,tau,v,v1
1e-3,1,1,10,0
1e-2,2,0.5,100,1
EOF
printf '[cases]\nfile = cases.csv\n[run]\nsamples = 5\n' >"$W/cases.ini"
# under load, the second of three cases fails (w1 = 1e100): /failures holds it
cat >"$W/failing.csv" <<'EOF'
# FN: the old spelling of the load F0, read as F0
FN,R,tau,v,w1,T1
5.333333333333333,1,1,1,0.5,1
5.333333333333333,1,1,1,1e100,1
5.333333333333333,1,1,1,2,1
EOF
printf '[cases]\nfile = failing.csv\n[run]\nsamples = 5\nrtol = 1e-3\n' >"$W/failing.ini"
study --config "$W/grid5.ini" --output "$W/grid5.h5"
study --config "$W/cases.ini" --output "$W/cases.h5"
study --config "$W/failing.ini" --output "$W/failing.h5"
ok "made grid5.h5 (48 cases, np = 2), cases.h5 and failing.h5"

# a copy as maps were before /schema: the same data and root attributes, no
# /schema, no dimension scales, no dataset attributes
cat >"$W/strip.py" <<'EOF'
# pyrun-needs: h5py
import sys
import h5py
with h5py.File(sys.argv[1], "r") as a, h5py.File(sys.argv[2], "w") as b:
    for k, v in a.attrs.items():
        b.attrs[k] = v
    def copy(name, obj):
        if name.startswith("schema") or name in ("case", "event", "sample"):
            return
        if isinstance(obj, h5py.Group):
            b.require_group(name)
        else:
            b.create_dataset(name, data=obj[()])
    a.visititems(copy)
    for k, v in a["grid"].attrs.items():
        if k in ("axes", "shape", "log"):
            b["grid"].attrs[k] = v
EOF
run strip py "$W/strip.py" "$W/grid5.h5" "$W/old.h5"

cat >"$W/check.py" <<'EOF'
# pyrun-needs: numpy h5py xarray h5netcdf
"""check.py TOOLS GRID5 CASES OLD: xarray sees named dimensions; to_grid is right."""
import sys
import warnings

import h5py
import numpy as np
import xarray as xr

from mdrmap.tools import mapxr  # (sys.argv[1]: the source tree's tools/, unused)
from mdrmap.tools._maplib import case_columns, schema

grid5, cases, old = sys.argv[2:5]
warnings.simplefilter("error")  # no phony-dimension or decoding warnings either
AXES = {"d": [1e-3, 1e-2], "R": [1.0, 2.0], "tau": [0.5, 2.0], "v": [0.1, 1.0, 10.0],
        "v1_over_v": [1e-3, 0.5]}
N = 48
# the map's own name of the step's axis, and a T1_over_tau axis of length 1 if it has one
with h5py.File(grid5, "r") as f:
    map_axes = f["grid"].attrs["axes"]
    map_axes = (map_axes.decode() if isinstance(map_axes, bytes) else str(map_axes)).split(",")
step = "w1_over_v" if "w1_over_v" in map_axes else "v1_over_v"
AXES[step] = AXES.pop("v1_over_v")
if [a for a in map_axes if a in AXES] != list(AXES):
    fail(f"/grid axes {map_axes}: not {list(AXES)} in this order")
for extra in [a for a in map_axes if a not in AXES]:  # e.g. T1_over_tau (or G): one value
    with h5py.File(grid5, "r") as f:
        if f["grid"][extra].shape != (1,):
            fail(f"/grid has the axis {extra} of length {f['grid'][extra].shape}")
        AXES[extra] = list(f["grid"][extra][()])
AXES = {a: AXES[a] for a in map_axes}  # the map's order


def fail(msg):
    sys.exit(f"check: {msg}")


# 1. plain xarray, group by group: named dimensions, units from /schema
with h5py.File(grid5, "r") as f:
    described = schema(f)
for group, dims in [("cases", {"case": N, "event": 1}), ("results", {"case": N}),
                    ("events", {"case": N, "event": 1}), ("analytic", {"case": N, "event": 1}),
                    ("residuals", {"case": N, "event": 1}), ("scales", {"case": N}),
                    ("timeseries", {"case": N, "sample": 7})]:
    with xr.open_dataset(grid5, engine="h5netcdf", group=group) as ds:
        if dict(ds.sizes) != dims:
            fail(f"group {group}: dimensions {dict(ds.sizes)}, expected {dims}")
        for name, var in ds.data_vars.items():
            unit, meaning = described[f"{group}/{name}"]
            if var.attrs.get("units") != unit or var.attrs.get("long_name") != meaning:
                fail(f"/{group}/{name}: attributes {var.attrs} vs /schema {unit!r} {meaning!r}")
    print(f"group {group}: {dims}")
with xr.open_dataset(grid5, engine="h5netcdf", group="grid") as g:
    if list(g.dims) != list(AXES) or set(g.coords) != set(AXES):
        fail(f"group grid: dimensions {dict(g.sizes)}, coordinates {list(g.coords)}")
    for a, vals in AXES.items():
        if not np.array_equal(g[a].values, vals):
            fail(f"/grid/{a} = {g[a].values}, expected {vals}")
    print(f"group grid: coordinates {dict(g.sizes)}")
if sorted(p for p in described if p.startswith("cases/")) != \
        sorted(f"cases/{c}" for c in ["d", "R", "tau", "G", "v", "w", "T"]):
    fail(f"/schema/cases lists {[p for p in described if p.startswith('cases/')]}")
if described["cases/d"][0] != "length" or described["cases/v"][0] != "length/time":
    fail(f"/schema units of d, v: {described['cases/d']}, {described['cases/v']}")

# 2. mapxr: one Dataset, and the 5-dimensional grid
ds = mapxr.open_map(grid5)
if dict(ds.sizes) != {"case": N, "event": 1, "sample": 7}:
    fail(f"open_map: dimensions {dict(ds.sizes)}")
for name in ["d", "G", "w", "T"]:
    if name not in ds.coords:
        fail(f"open_map: /cases/{name} is not a coordinate")
for name in ["mu_after", "mu_peak", "a", "D_c", "status", "message", "analytic_mu_jump",
             "analytic_mu_ss", "residual_mu_end", "scale_length", "scale_time", "ts_mu",
             "ts_segment"]:
    if name not in ds.data_vars:
        fail(f"open_map: no variable {name}")
if ds["FN_pre"].attrs.get("units") != "force" or ds["d"].attrs.get("units") != "length":
    fail(f"open_map: units {ds['FN_pre'].attrs} {ds['d'].attrs}")
g = mapxr.to_grid(ds)
# the axes of more than one value are the dimensions; one of one value (G,
# T1_over_tau) is a scalar coordinate
DIMS = {a: v for a, v in AXES.items() if len(v) > 1}
want_dims = dict({a: len(v) for a, v in DIMS.items()}, event=1, sample=7)
if dict(g.sizes) != want_dims or list(g["mu_after"].dims) != list(DIMS) + ["event"]:
    fail(f"to_grid: dimensions {dict(g.sizes)} ({g['mu_after'].dims}), expected {want_dims}")
for a, vals in DIMS.items():
    if not np.array_equal(g[a].values, vals) or a not in g.indexes:
        fail(f"to_grid: coordinate {a} = {g[a].values}, expected {vals}")
for a, vals in AXES.items():
    if a not in DIMS and (g[a].ndim != 0 or float(g[a]) != vals[0]):
        fail(f"to_grid: {a} is not the scalar coordinate {vals[0]}: {g[a]}")
if g["ts_mu"].dims != tuple(DIMS) + ("sample",):
    fail(f"to_grid: ts_mu dimensions {g['ts_mu'].dims}")
for name, var in ds.variables.items():
    if name in AXES:
        continue
    if "case" not in var.dims:
        continue  # ts_segment: not along the cases
    flat = g[name].values.reshape((N,) + var.shape[1:])
    if not np.array_equal(flat, var.values, equal_nan=var.dtype.kind == "f"):
        fail(f"to_grid: {name} differs from the 1-D rows")
# and point by point: the case at given axis values is the row with those parameters
pick = g.sel({"d": 1e-2, "R": 2.0, "tau": 0.5, "v": 10.0, step: 1e-3}).squeeze()
i = int(pick["case"])
row = ds.isel(case=i)
for a in ["d", "R", "tau", "v"]:
    if float(row[a]) != float(pick[a]):
        fail(f"to_grid: case {i} has {a} = {float(row[a])}, the grid point {float(pick[a])}")
if float(row["mu_after"].squeeze()) != float(pick["mu_after"].squeeze()):
    fail("to_grid: mu_after at a grid point is not its row's")
print(f"to_grid: {dict(g.sizes)}; coordinates {', '.join(g.indexes)}; "
      f"{len(g.data_vars)} variables equal the 1-D rows")
ds.close()

# 3. a [cases] map: merged, but no grid
c = mapxr.open_map(cases)
if dict(c.sizes) != {"case": 2, "event": 1}:
    fail(f"cases map: dimensions {dict(c.sizes)}")
try:
    mapxr.to_grid(c)
    fail("to_grid accepted a [cases] map")
except mapxr.UserError as e:
    print(f"cases map: to_grid refuses: {e}")
c.close()

# 4. a map as written before /schema and the dimension scales
with h5py.File(old, "r") as f:
    if schema(f) or case_columns(f):
        fail(f"old map: schema {schema(f)} columns {case_columns(f)}")
warnings.simplefilter("default")
o = mapxr.open_map(old)
if dict(o.sizes) != {"case": N, "event": 1, "sample": 7}:
    fail(f"old map: dimensions {dict(o.sizes)}")
go = mapxr.to_grid(o)
if not np.array_equal(go["mu_after"].values, g["mu_after"].values):
    fail("old map: to_grid differs from the new map's")
print("old map (no /schema, no scales): opens with dimensions case, event, sample; same grid")
o.close()
EOF
cat >"$W/walk.py" <<'EOF'
# pyrun-needs: numpy h5py xarray h5netcdf
"""walk.py MAP...: every group of each map opens with xarray, no phony dimensions."""
import sys
import warnings

import h5py
import numpy as np
import xarray as xr

warnings.simplefilter("error")
NONE = np.iinfo(np.uint64).max  # /failures/case of an unused slot
for path in sys.argv[1:]:
    with h5py.File(path, "r") as f:
        groups = [""]
        f.visititems(lambda name, obj: groups.append(name) if isinstance(obj, h5py.Group) else None)
        status = f["results/status"][()]
    for group in groups:
        try:
            with xr.open_dataset(path, engine="h5netcdf", group=group or None) as ds:
                ds.load()
        except (ValueError, OSError) as e:
            sys.exit(f"walk: {path}: group /{group}: {str(e).splitlines()[0]}")
    with xr.open_dataset(path, engine="h5netcdf", group="failures") as ds:
        if list(ds.sizes) != ["failure"] or ds.sizes["failure"] != status.size:
            sys.exit(f"walk: {path}: /failures dimensions {dict(ds.sizes)}: one slot per case")
        case = ds["case"].values
        used = case != NONE
        if sorted(case[used]) != list(np.flatnonzero(status == -1)):
            sys.exit(f"walk: {path}: /failures/case {case[used]}, failed {np.flatnonzero(status == -1)}")
        if any(len(m) == 0 for m in ds["message"].values[used]):
            sys.exit(f"walk: {path}: a failed case without a message")
    with xr.open_dataset(path, engine="h5netcdf", group="provenance") as ds:
        text = bytes(ds["config_text"].values).decode()
        if "[run]" not in text or set(ds.sizes) != {"config_text_byte", "config_canonical_byte"}:
            sys.exit(f"walk: {path}: /provenance {dict(ds.sizes)}: {text[:40]!r}")
    print(f"{path}: {len(groups)} groups open with xarray; /failures lists "
          f"{int(used.sum())} failed case(s)")
EOF
run walk py "$W/walk.py" "$W/grid5.h5" "$W/cases.h5" "$W/failing.h5"
cat "$W/walk.out"
grep -q "failing.h5: .* lists 1 failed case" "$W/walk.out" || fail "walk: the failed case of failing.h5"
ok "xarray: every group of every map opens, /failures and /provenance included"
run check py "$W/check.py" "$SRCDIR/tools" "$W/grid5.h5" "$W/cases.h5" "$W/old.h5"
cat "$W/check.out"
ok "xarray: named dimensions in every group, /grid coordinates; mapxr.to_grid: 5-d, coordinates" \
  "= axis values, values = rows; old maps open"

# the command line
run help py "$XR" --help
expect() { grep -qF -- "$3" "$2" || { cat "$2" >&2; fail "$1: '$3' not in $2"; }; }
expect help "$W/help.out" "to_grid(ds)"
run cli py "$XR" "$W/grid5.h5" --grid --var mu_after
grep -qE "\(d, R, tau, v, v1_over_v, event\) float64" "$W/cli.out" ||
  { cat "$W/cli.out" >&2; fail "cli: mu_after is not over the grid's axes and event"; }
# a 32-term spectrum (68 axes, two of its terms varied): --grid makes the
# varied terms one dimension `material` and the axes of one value scalars
{
  printf '[grid]\nd = 1e-3\nR = 1\ntau = 0\nG = 1\nG1 = 1, 2\ntau1 = 0.01\n'
  for ((k = 2; k <= 32; k++)); do printf 'G%d = 1\ntau%d = %s\n' "$k" "$k" "$((k == 2 ? 1 : k))"; done
  printf 'v = 0.1, 1\nv1_over_v = 2\n[run]\nsamples = 5\nrtol = 1e-3\n'
} >"$W/spectrum.ini"
sed -i 's/^tau2 = 1$/tau2 = 1, 10/' "$W/spectrum.ini"
study --config "$W/spectrum.ini" --output "$W/spectrum.h5"
run cli_spectrum py "$XR" "$W/spectrum.h5" --grid --var mu_after
grep -qE "mu_after +\(material, v, event\) float64" "$W/cli_spectrum.out" &&
  grep -qE "^ +G1 +\(material\) float64 1.0 1.0 2.0 2.0" "$W/cli_spectrum.out" ||
  { cat "$W/cli_spectrum.out" >&2; fail "cli: a spectrum's varied terms are not one material axis"; }
bad() {
  local name=$1 expected=$2 rc=0
  shift 2
  "$@" >"$W/$name.out" 2>"$W/$name.err" || rc=$?
  if ((rc != 2)) || (($(wc -l <"$W/$name.err") != 1)) || ! grep -qF -- "$expected" "$W/$name.err"
  then
    cat "$W/$name.err" >&2
    fail "$name: expected exit 2 and one line with '$expected' (exit $rc)"
  fi
  ok "$name: exit 2: $(cat "$W/$name.err")"
}
bad cli_missing "no such file" py "$XR" "$W/absent.h5"
bad cli_not_map "is not a readable HDF5 file" py "$XR" "$W/grid5.ini"
bad cli_cases_grid "not a grid study" py "$XR" "$W/cases.h5" --grid
bad cli_var "--var foo: no such variable" py "$XR" "$W/grid5.h5" --var foo
ok "mapxr.py: --help, --grid --var (a 32-term spectrum too), one-line errors"

# the tools read units and scales from the map: one without /schema (older
# maps) or without /scales (made before mdrmap wrote them) is refused in one line
cat >"$W/noscales.py" <<'EOF'
# pyrun-needs: h5py
import shutil, sys
import h5py
shutil.copy(sys.argv[1], sys.argv[2])
with h5py.File(sys.argv[2], "r+") as f:
    del f["scales"]
EOF
run noscales py "$W/noscales.py" "$W/grid5.h5" "$W/noscales.h5"
bad ms_old "old.h5 has no /schema group: it was made before mdrmap wrote /schema" \
  py "$MS" "$W/old.h5" --no-config
bad ms_noscales "noscales.h5 has no /scales group: it was made before mdrmap wrote /scales" \
  py "$MS" "$W/noscales.h5" --no-config
run ms_new py "$MS" "$W/grid5.h5" --no-config --csv "$W/new.csv"
expect ms_new "$W/ms_new.out" "zeta = v tau / a1 (/scales: time over length)"
ok "map_summary: reads /schema and /scales; refuses a map without either in one line"

echo "PASS: xarray view of maps ($checks checks)"
