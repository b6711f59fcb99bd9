#!/usr/bin/env python3
# pyrun-needs: numpy h5py xarray h5netcdf
"""Open an mdrmap map as an xarray Dataset; turn a grid study into an N-dimensional one.

As a module (with tools/ on sys.path):

    import mapxr
    ds = mapxr.open_map("MAP.h5")   # one Dataset: every per-case dataset of the map
    g = mapxr.to_grid(ds)           # grid maps: one dimension per grid axis

open_map(path) merges the map's groups into one Dataset with dimension
`case` (and `event` for per-event values, `sample` for the time series). It
reads both layouts (the root attribute mdrmap_schema):

  - /cases columns as coordinates along `case` (mdrmap-map/2: d or FN, R, tau,
    G, v, and w and T over (case, event); mdrmap-map/1: d, R, tau, v, v1, G);
  - /results under their bare names (FN_pre, error_estimate, wall_seconds,
    status; mdrmap-map/1 also mu_jump, mu_post, ...), and `message`: why a
    case failed ('' otherwise; mdrmap-map/2: from /failures/{case,message});
  - /events (mdrmap-map/2) under their bare names over (case, event): t,
    mu_after, mu_peak, a, b, a_minus_b, d_c, ...; undefined values (the netCDF
    fill value) are NaN;
  - /analytic as analytic_<name>, /residuals as residual_<name> (the names of
    map_summary.py's CSV), /timeseries as ts_<name> over (case, sample)
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

to_grid(ds) reshapes every variable along `case` to the grid's axes (C order,
last axis fastest: the case order of a [grid] study), with the axis values as
index coordinates, the other /cases columns (e.g. v1, G; w and T) as N-d
coordinates, and a coordinate `case` holding each point's row number in the
map. The axes of an mdrmap-map/2 grid include the history's (w1_over_v,
T1_over_tau, w2, ...: dimensions like any other). It checks that the /cases
columns equal the grid (v1 = v1_over_v * v, wk = w[:, k-1], wk_over_v =
w[:, k-1] / v, Tk_over_tau = T[:, k-1] / tau, to 1e-12).

Command line: prints the Dataset (with --grid, the N-dimensional one).

Usage:
    tools/pyrun tools/mapxr.py MAP.h5
    tools/pyrun tools/mapxr.py MAP.h5 --grid
    tools/pyrun tools/mapxr.py MAP.h5 --grid --var mu_peak --var residual_mu_pre

Exit codes: 0 success, 2 bad input (one line on stderr).
"""

import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from maplib import (Parser, UserError, failure_messages, open_map as open_h5,  # noqa: E402
                    run_tool, schema_version, segment_axis, text)

PROG = "mapxr"
# map group -> variable name prefix
GROUPS = [("cases", ""), ("results", ""), ("events", ""), ("analytic", "analytic_"),
          ("residuals", "residual_"), ("timeseries", "ts_")]


def _attr(value):
    """An HDF5 attribute as a plain Python/numpy value (strings as str)."""
    import numpy as np

    if isinstance(value, (bytes, np.bytes_)) or getattr(value, "dtype", None) is not None and \
            value.dtype.kind == "S":
        return text(value).rstrip("\0")
    if isinstance(value, np.ndarray) and value.ndim == 0:
        return value.item()
    return value


def _read_h5(path):
    """Root attributes, /grid description and which groups the map has (h5py)."""
    import h5py
    import numpy as np

    with open_h5(path, h5py, PROG) as f:
        attrs = {k: _attr(f.attrs[k]) for k in f.attrs}
        n = int(f["results/status"].shape[0])
        groups = [g for g, _ in GROUPS if g in f and hasattr(f[g], "keys") and len(f[g])]
        grid = None
        if "grid" in f:
            g = f["grid"]
            try:
                axes = [a.strip() for a in text(g.attrs["axes"]).split(",") if a.strip()]
                values = [np.asarray(g[a][()], dtype=float) for a in axes]
                log = [int(k) for k in np.ravel(g.attrs["log"])] if "log" in g.attrs \
                    else [0] * len(axes)
                described = {a: (text(g[a].attrs.get("units", "")), text(g[a].attrs.get(
                    "long_name", ""))) for a in axes}
            except (KeyError, ValueError) as e:
                raise UserError(f"{path}: /grid is malformed ({e})") from None
            if math.prod(len(v) for v in values) != n:
                raise UserError(f"{path}: /grid axes {axes} of shape "
                                f"{[len(v) for v in values]} do not fit {n} cases")
            grid = {"axes": axes, "values": values, "log": log, "described": described}
        scaled = "case" in f and f["case"].attrs.get("CLASS") == b"DIMENSION_SCALE"
        version = schema_version(f)
        messages = failure_messages(f, n) if version == 2 else None
    return attrs, n, groups, grid, scaled, version, messages


def open_map(path):
    """The map at `path` as one xarray Dataset (see the module's help). Raises
    UserError (one line) when `path` is not a readable mdrmap map."""
    import xarray as xr

    import numpy as np

    attrs, n, groups, grid, scaled, version, messages = _read_h5(path)
    parts = []
    for group, prefix in GROUPS:
        if group not in groups:
            continue
        try:
            # mdrmap-map/2: the fill value of undefined values becomes NaN
            ds = xr.open_dataset(path, engine="h5netcdf", group=group, decode_times=False,
                                 decode_timedelta=False, mask_and_scale=version == 2,
                                 phony_dims=None if scaled else "sort")
        except (OSError, ValueError) as e:
            raise UserError(f"{path}: cannot open /{group} with xarray "
                            f"({str(e).splitlines()[0]})") from None
        if not scaled:  # a map without dimension scales: name the phony dimensions
            second = "sample" if group == "timeseries" else "event"
            names = {}
            for var in ds.data_vars.values():
                want = ["case", second] if len(var.dims) == 2 or var.shape[0] == n else [second]
                for dim, name in zip(var.dims, want):
                    if names.setdefault(dim, name) != name:
                        raise UserError(f"{path}: /{group} has no dimension scales and its "
                                        f"dimensions are ambiguous")
            ds = ds.rename_dims(names)
        if ds.sizes.get("case") != n:
            raise UserError(f"{path}: /{group} is not along the {n} cases")
        for name in ds.data_vars:
            ds[name].attrs["map_path"] = f"{group}/{name}"
        ds = ds.rename({k: prefix + k for k in ds.data_vars}) if prefix else ds
        if group == "cases":
            ds = ds.set_coords(list(ds.data_vars))
        ds.attrs = {}
        parts.append(ds)
    out = xr.merge(parts, compat="identical", join="exact", combine_attrs="override")
    if messages is not None:
        out["message"] = xr.Variable(("case",), np.array(messages, dtype=object),
                                     {"long_name": "why a case failed (empty otherwise)",
                                      "map_path": "failures/message"})
    out.attrs = dict(attrs)
    if grid:
        out.attrs["grid_axes"] = ",".join(grid["axes"])
        out.attrs["grid_shape"] = [len(v) for v in grid["values"]]
        out.attrs["grid_log"] = grid["log"]
        for a, v in zip(grid["axes"], grid["values"]):
            out.attrs[f"grid_{a}"] = v
            unit, meaning = grid["described"][a]
            if unit:
                out.attrs[f"grid_{a}_units"] = unit
            if meaning:
                out.attrs[f"grid_{a}_long_name"] = meaning
    return out


def to_grid(ds):
    """The Dataset of a grid study (open_map) with the grid's axes as dimensions
    (see the module's help). Raises UserError for a map without /grid."""
    import numpy as np
    import xarray as xr

    if "grid_axes" not in ds.attrs:
        raise UserError("not a grid study (the map has no /grid): to_grid needs the grid's axes")
    axes = [a for a in str(ds.attrs["grid_axes"]).split(",") if a]
    values = [np.asarray(ds.attrs[f"grid_{a}"], dtype=float) for a in axes]
    shape = tuple(len(v) for v in values)
    n = ds.sizes["case"]
    if math.prod(shape) != n:
        raise UserError(f"grid axes {axes} of shape {list(shape)} do not fit {n} cases")
    clash = [a for a in axes if a in ds.dims]
    if clash:
        raise UserError(f"grid axis {clash[0]!r} is also a dimension of the Dataset")

    # the /cases columns must be the grid, in C order (last axis fastest)
    mesh = dict(zip(axes, np.meshgrid(*values, indexing="ij")))
    if "v1_over_v" in mesh and "v" in mesh:
        mesh.setdefault("v1", mesh["v1_over_v"] * mesh["v"])
    for a, want in mesh.items():
        seg = segment_axis(a) if a not in ds.variables else None
        if seg is not None and seg[0] in ds.variables and ds[seg[0]].ndim == 2:
            # an mdrmap-map/2 history axis: from /cases/w or /cases/T [N, K]
            kind, k, over = seg
            col = np.asarray(ds[kind].values, dtype=float)
            if k > col.shape[1]:
                raise UserError(f"grid axis {a!r} names segment {k}, the map has {col.shape[1]}")
            have = col[:, k - 1]
            if over:
                ref = np.asarray(ds["v" if kind == "w" else "tau"].values, dtype=float)
                with np.errstate(divide="ignore", invalid="ignore"):
                    have = np.where(ref != 0, have / ref, np.nan)
            have = have.reshape(shape)
            ok = np.isfinite(have)  # Tk_over_tau at tau = 0: not a multiple of tau
            same = np.allclose(have[ok], want[ok], rtol=1e-12, atol=0)
        elif a not in ds.variables:
            continue
        else:
            have = np.asarray(ds[a].values, dtype=float).reshape(shape)
            exact = a in axes
            same = np.array_equal(have, want) if exact else \
                np.allclose(have, want, rtol=1e-12, atol=0)
        if not same:
            raise UserError(f"/cases/{a} does not follow the grid's axes {axes} in C order: "
                            f"not a grid study's case order")

    coords = {}
    for a, v in zip(axes, values):
        attrs = {}
        for key in ("units", "long_name"):
            if f"grid_{a}_{key}" in ds.attrs:
                attrs[key] = ds.attrs[f"grid_{a}_{key}"]
        coords[a] = xr.Variable((a,), v, attrs)
    coords["case"] = xr.Variable(tuple(axes), np.arange(n).reshape(shape),
                                 {"long_name": "row of the case in the map"})
    data = {}
    for name, var in ds.variables.items():
        if name in axes:
            continue  # now an index coordinate
        if "case" not in var.dims:  # e.g. ts_segment: kept as it is
            (coords if name in ds.coords else data)[name] = var
            continue
        if var.dims[0] != "case" or "case" in var.dims[1:]:
            raise UserError(f"variable {name!r} is not along `case` first: cannot reshape it")
        rest = var.dims[1:]
        arr = np.asarray(var.values)
        new = xr.Variable(tuple(axes) + rest, arr.reshape(shape + arr.shape[1:]), var.attrs)
        if name in ds.coords:
            coords[name] = new
        else:
            data[name] = new
    attrs = {k: v for k, v in ds.attrs.items()}
    return xr.Dataset(data, coords=coords, attrs=attrs)


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
