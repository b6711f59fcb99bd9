# pyrun-needs: numpy h5py xarray h5netcdf
"""Open an mdrmap map as an xarray Dataset; turn a grid study into an N-dimensional one.

As a module:

    from mdrmap.tools import mapxr
    ds = mapxr.open_map("MAP.h5")   # one Dataset: every per-case dataset of the map
    g = mapxr.to_grid(ds)           # grid maps: one dimension per grid axis

open_map(path) merges the map's groups into one Dataset with dimension
`case` (and `event` for per-event values, `sample` for the time series). It
reads both layouts (the root attribute mdrmap_schema):

  - /cases columns as coordinates along `case` (mdrmap-map/2: d or F0, R, tau,
    G, v, and w and T over (case, event); mdrmap-map/1: d, R, tau, v, v1, G);
  - /results under their bare names (FN_pre, error_estimate, wall_seconds,
    status; mdrmap-map/1 also mu_jump, mu_post, ...), and `message`: why a
    case failed ('' otherwise; mdrmap-map/2: from /failures/{case,message});
  - /events (mdrmap-map/2) under their bare names over (case, event): t,
    mu_after, mu_peak, a, b, a_minus_b, D_c, ...; undefined values (the netCDF
    fill value) are NaN;
  - /analytic as analytic_<name>, /residuals as residual_<name>, /scales as
    scale_<name> (each case's reference length, depth, force, friction and
    time; the names of map_summary.py's CSV), /timeseries as ts_<name> over
    (case, sample)
    (mdrmap-map/2: also ts_segment over sample, the segment of each sample);
  - each variable with the attributes units and long_name from the map's
    /schema (maps written before /schema have none) and map_path (its
    dataset in the map);
  - the Dataset's attributes: the map's root attributes (provenance) and, for
    a grid study, grid_axes (comma list), grid_shape, grid_log and
    grid_<axis> (the axis values).

Maps with dimension scales are opened lazily (xarray engine h5netcdf, the
file stays open until ds.close()); older maps too, their phony dimensions
renamed to case and sample.

to_grid(ds) reshapes every variable along `case` to the grid's axes of more
than one value (C order, last axis fastest: the case order of a [grid]
study), with the axis values as index coordinates; an axis of one value (a
fixed d, G, T1_over_tau, a spectrum's fixed terms) is a scalar coordinate;
a relaxation spectrum's varied terms (G1, tau1, ..., G32, tau32) are one
dimension `material` (their combinations in C order, each term a coordinate
along it), so a spectrum of 32 terms fits numpy's dimensions. The other
/cases columns (e.g. v1; w and T) are N-d coordinates, and a coordinate
`case` holds each point's row number in the map. The axes of an
mdrmap-map/2 grid include the history's (w1_over_v, T1_over_tau, w2, ...:
dimensions like any other). It checks that the /cases
columns equal the grid (v1 = v1_over_v * v, wk = w[:, k-1], wk_over_v =
w[:, k-1] / v, Tk_over_tau = T[:, k-1] / tau, to 1e-12).

The code is the Python package's (src/python/mdrmap/maps.py, mdrmap.open_map
and mdrmap.to_grid); this file loads it from the source tree, so it needs no
build, and is its command line: prints the Dataset (with --grid, the
N-dimensional one).

Usage:
    python3 -m mdrmap mapxr MAP.h5
    python3 -m mdrmap mapxr MAP.h5 --grid
    python3 -m mdrmap mapxr MAP.h5 --grid --var mu_peak --var residual_mu_pre

Exit codes: 0 success, 2 bad input (one line on stderr).
"""

import argparse
import sys
import warnings

from ._maplib import Parser, UserError, run_tool
from .. import maps as _maps

PROG = "mapxr"



def open_map(path):
    """The map at `path` as one xarray Dataset (mdrmap.open_map). Raises
    UserError (one line) when `path` is not a readable mdrmap map."""
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", _maps.MapWarning)
            ds = _maps.open_map(path)
    except _maps.MapError as e:
        raise UserError(str(e)) from None
    for w in caught:  # the map's schema warning in one line, as the other tools give it
        if issubclass(w.category, _maps.MapWarning):
            print(f"{PROG}: warning: {w.message}", file=sys.stderr)
        else:
            warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    return ds


def to_grid(ds):
    """The Dataset of a grid study with the grid's axes as dimensions
    (mdrmap.to_grid). Raises UserError for a map without /grid."""
    try:
        return _maps.to_grid(ds)
    except _maps.MapError as e:
        raise UserError(str(e)) from None


def main(argv=None):
    ap = Parser(prog=PROG, description=__doc__,
                formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("map", help="mdrmap map (.h5)")
    ap.add_argument("--grid", action="store_true",
                    help="print the N-dimensional Dataset of a grid study (to_grid)")
    ap.add_argument("--var", action="append", metavar="NAME",
                    help="print only these variables (repeatable), e.g. mu_peak, residual_mu_pre")
    args = ap.parse_args(argv)
    ds = open_map(args.map)
    try:
        if args.var:
            unknown = [v for v in args.var if v not in ds.variables]
            if unknown:
                raise UserError(f"--var {unknown[0]}: no such variable (variables: "
                                f"{', '.join(ds.data_vars)})")
            keep = [v for v in args.var if v not in ds.coords]
            ds = ds[keep] if keep else ds.drop_vars(list(ds.data_vars))
        out = to_grid(ds) if args.grid else ds
        print(out)
    finally:
        ds.close()
    return 0


if __name__ == "__main__":
    sys.exit(run_tool(main, PROG))
