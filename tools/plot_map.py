#!/usr/bin/env python3
# pyrun-needs: numpy matplotlib h5py
"""Colour map of one or more quantities of an mdrmap map over two parameters.

QUANTITY is a dataset of /results, /analytic or /residuals: a bare name
(`mu_jump`, `FN_pre`, `mu_inf`, `error_estimate`) is looked up in /results,
then /analytic, then /residuals; a prefixed one (`analytic/mu_post`,
`residuals/mu_jump`) names its group. Several quantities give one panel each.
Default: mu_jump (the friction coefficient right after the step).

mdrmap-map/2 maps (a history of K segments, docs/map-schema.md) are read too:
their per-event datasets ([N, K]: /events, analytic/<q>_ss, residuals/<q>_end)
are quantities <name>_<k> for event k, e.g. `mu_after_0` (the friction just
after the change at t = 0: the default), `mu_peak_1`, `a_0`, `d_c_0`,
`analytic/mu_ss_0`, `residuals/mu_end_0`; bare names are looked up in
/results, /events, /analytic, /residuals, in that order. Undefined values
(the fill value) are drawn grey like cases not done. The grid's axes include
the history's (w1_over_v, T1_over_tau, ...); `--slice v1_over_v=...` finds
w1_over_v. `--scaled` divides mu by a/R and lengths by a, a = a1 = sqrt(R d)
at depth or a0 = (3 FN R / (16 G))^(1/3) under load (forces by G a^3 / R);
`--similarity` plots over zeta = v tau / a and zeta1 = w1 tau / a.

Grid maps (with /grid): rows are reshaped with the /grid attributes `axes`,
`shape` (C order, last axis fastest) and drawn over two grid axes, `--x` and
`--y` (default: the two axes with the most values, the longer one on x; on a
tie the later axis of /grid attribute `axes` goes on x). Every
other axis with more than one value is sliced at one value: `--slice R=2`
takes the grid value nearest to 2 (the value used is printed), an axis
without `--slice` is taken at its first value. An axis is logarithmic when
the grid says so (attribute `log`) or its values are geometric; a list that is
neither evenly nor geometrically spaced is drawn as categories. With only one
axis of more than one value the result is a line plot.

`--similarity` plots over zeta = v tau / a1 and zeta1 = v1 tau / a1 (a1 =
sqrt(R d)) instead, as a scatter (and filled contours where the points span
an area), with the similarity scales applied (see `--scaled`); it also
prints how far cases sharing (zeta, zeta1) differ, which checks the collapse.
Maps written from a [cases] list (no /grid) are drawn as a scatter over two
/cases columns (default: the two with the most distinct values).

`--scaled` divides by the natural scales: F_N / (G a1 d), F_x / (G d^2),
mu / sqrt(d/R), a2 / a1. Residuals use a symmetric diverging colour map.
Cases that are pending or failed are drawn grey (not-done) and counted.

Usage:
    tools/pyrun tools/plot_map.py MAP.h5 -o map.png
    tools/pyrun tools/plot_map.py MAP.h5 mu_pre mu_jump --x v --y d --log-color -o mu.png
    tools/pyrun tools/plot_map.py MAP.h5 residuals/mu_jump --slice R=1 -o res.png
    tools/pyrun tools/plot_map.py MAP.h5 mu_jump --similarity -o sim.png

Exit codes: 0 success, 2 bad input (one line on stderr).
"""

import argparse
import math
import os
import sys

from maplib import (CASE_COLS, Parser, UserError, case_columns, load_cases, open_map,
                    read_masked, resolve_axis, run_tool, save_figure, schema, schema_version, text)

PROG = "plot_map"
GROUPS = ["results", "analytic", "residuals"]
GROUPS2 = ["results", "events", "analytic", "residuals"]  # mdrmap-map/2
DERIVED = ["v1_over_v", "zeta", "zeta1"]
SYMBOL = {"FN": "F$_N$", "Fx": "F$_x$", "mu": "\u03bc", "a2": "a$_2$", "a1": "a$_1$", "d": "d"}
NAME = {"FN": "normal force", "Fx": "friction force", "mu": "friction coefficient",
        "a2": "trailing edge", "a1": "leading edge", "d": "depth"}
UNIT = {"FN": "[G length$^2$]", "Fx": "[G length$^2$]", "mu": "", "a2": "[length]",
        "a1": "[length]", "d": "[length]"}
SCALED = {"FN": "F$_N$ / (G a$_1$ d)", "Fx": "F$_x$ / (G d$^2$)", "mu": "\u03bc / \u221a(d/R)",
          "a2": "a$_2$ / a$_1$"}
COLNAME = {"d": "depth d", "R": "radius R", "tau": "\u03c4 = \u03b7/G", "v": "velocity v",
           "v1": "velocity v$_1$ after the step", "G": "shear modulus G",
           "v1_over_v": "v$_1$ / v", "zeta": "\u03b6 = v\u03c4/a$_1$",
           "zeta1": "\u03b6$_1$ = v$_1$\u03c4/a$_1$"}
# mdrmap-map/2: a = a1 = sqrt(R d) at depth, a0 (Hertz radius of FN) under load
SCALED2 = {"FN": "F$_N$ / (G a$^3$/R)", "Fx": "F$_x$ / (G a$^3$/R)", "mu": "\u03bc / (a/R)",
           "a2": "a$_2$ / a", "a1": "a$_1$ / a", "d": "d / (a$^2$/R)"}
LABEL_BOX = {"facecolor": "white", "alpha": 0.7, "edgecolor": "none", "pad": 0.6}


def fmt(x):
    """Compact number: 1e-04 -> 1e-4, 0.5 -> 0.5."""
    x = float(x)
    if x == 0 or not math.isfinite(x):
        return str(x if x else 0)
    s = f"{x:.3g}" if 1e-3 <= abs(x) < 1e4 else f"{x:.2e}"
    if "e" in s:
        mant, exp = s.split("e")
        mant = mant.rstrip("0").rstrip(".") if "." in mant else mant
        return f"{mant}e{int(exp)}"
    return s


# ----------------------------------------------------------------- reading

def load2(f, path, np):
    """An mdrmap-map/2 map in the form the plots read (per-event datasets as
    <group>/<name>_<k>)."""
    c = load_cases(f, path, np)
    n, K = c["n"], c["K"]
    m = {"path": path, "version": 2, "data": {}, "n": n, "status": c["status"],
         "schema": schema(f), "mu_scale": c["mu_scale"], "a": c["a"]}
    seg = [f"{kind}{j + 1}" for j in range(K) for kind in ("w", "T")]
    m["case_cols"] = list(c["cols"]) + seg
    m.update(c["cols"])
    for j in range(K):
        m[f"w{j + 1}"], m[f"T{j + 1}"] = c["w"][:, j], c["T"][:, j]
    with np.errstate(divide="ignore", invalid="ignore"):
        m["zeta"] = c["zeta"]
        m["zeta1"] = c["w"][:, 0] * c["cols"]["tau"] / c["a"]
    m["derived"] = ["zeta", "zeta1"]
    for grp in GROUPS2:
        if grp not in f:
            continue
        for name, ds in f[grp].items():
            if not hasattr(ds, "dtype") or ds.dtype.kind not in "fiu":
                continue
            if ds.shape == (n,):
                m["data"][f"{grp}/{name}"] = read_masked(ds).astype(float)
            elif len(ds.shape) == 2 and ds.shape[0] == n:
                x = read_masked(ds).astype(float)
                for j in range(ds.shape[1]):
                    m["data"][f"{grp}/{name}_{j}"] = x[:, j]
    grid = c["grid"]
    m["grid"] = dict(grid, log=[bool(k) for k in grid["log"]]) if grid else None
    return m


def load(path, np, h5py):
    f = open_map(path, h5py, PROG)
    if schema_version(f) == 2:
        with f:
            return load2(f, path, np)
    m = {"path": path, "data": {}, "version": 1, "derived": DERIVED}
    with f:
        n = f["results/status"].shape[0]
        m["n"] = n
        m["status"] = f["results/status"][()].astype(int)
        # units and meanings from /schema ({} for older maps); the /cases columns
        # from it too (older maps: CASE_COLS), with those the derived variables need
        m["schema"] = schema(f)
        m["case_cols"] = case_columns(f, m["schema"])
        for c in m["case_cols"] + [c for c in CASE_COLS if c not in m["case_cols"]]:
            m[c] = f[f"cases/{c}"][()].astype(float) if f"cases/{c}" in f else np.ones(n)
        for grp in GROUPS:
            if grp not in f:
                continue
            for name, ds in f[grp].items():
                if hasattr(ds, "dtype") and ds.dtype.kind in "fiu" and ds.shape == (n,):
                    m["data"][f"{grp}/{name}"] = ds
        m["data"] = {k: v[()].astype(float) for k, v in m["data"].items()}
        m["grid"] = None
        if "grid" in f:
            g = f["grid"]
            try:
                axes = [a.strip() for a in text(g.attrs["axes"]).split(",") if a.strip()]
                shape = [int(k) for k in np.ravel(g.attrs["shape"])]
                log = [bool(k) for k in np.ravel(g.attrs["log"])] if "log" in g.attrs \
                    else [False] * len(axes)
                values = [g[a][()].astype(float) for a in axes]
            except (KeyError, ValueError) as e:
                raise UserError(f"{path}: /grid is malformed ({e})") from None
            if len(shape) != len(axes) or int(np.prod(shape)) != n or \
                    any(len(v) != k for v, k in zip(values, shape)):
                raise UserError(f"{path}: /grid axes {axes} and shape {shape} do not fit "
                                f"{n} cases")
            m["grid"] = {"axes": axes, "shape": shape, "log": log, "values": values}
    with np.errstate(divide="ignore", invalid="ignore"):
        m["a1"] = np.sqrt(m["R"] * m["d"])
        m["v1_over_v"] = m["v1"] / m["v"]
        m["zeta"] = m["v"] * m["tau"] / m["a1"]
        m["zeta1"] = m["v1"] * m["tau"] / m["a1"]
    return m


def resolve(m, name):
    key = name.strip().strip("/")
    if "/" in key:
        if key in m["data"]:
            return key
    else:
        for grp in (GROUPS2 if m.get("version") == 2 else GROUPS):
            if f"{grp}/{key}" in m["data"]:
                return f"{grp}/{key}"
    bare = sorted({k.split("/", 1)[1] for k in m["data"]},
                  key=lambda s: (s.split("_")[0] not in SYMBOL, s))
    if m.get("version") == 2:
        raise UserError(f"unknown quantity {name!r}; valid: {', '.join(bare)} (bare names come "
                        f"from /results, /events, then /analytic; <name>_<k> is event k; prefix "
                        f"analytic/ or residuals/ for those groups, e.g. residuals/mu_end_0)")
    raise UserError(f"unknown quantity {name!r}; valid: {', '.join(bare)} "
                    f"(bare names come from /results, then /analytic; prefix analytic/ or "
                    f"residuals/ for those groups, e.g. residuals/mu_jump)")


def base_of(key):
    """'results/mu_jump' -> ('results', 'mu', 'jump')."""
    grp, name = key.split("/", 1)
    parts = name.split("_", 1)
    return grp, parts[0], parts[1] if len(parts) > 1 else ""


def describe(key, scaled, described=None, v2=False):
    """Colour bar label and short title for a dataset (one this tool does not know:
    its meaning and unit from the map's /schema, `described`)."""
    grp, q, when = base_of(key)
    name = key.split("/", 1)[1]
    if q not in SYMBOL:
        extra = {"error_estimate": "solver error estimate", "wall_seconds": "wall time per case [s]",
                 "status": "status (1 done, 0 pending, -1 failed)"}
        if name not in extra and key in (described or {}):
            unit, meaning = described[key]
            return f"{meaning} [{unit}]" if unit else meaning, name
        return extra.get(name, name), name
    what = {
        "pre": "stationary before the step (at v)",
        "jump": "just after the step (t = 0+)",
        "post": "stationary at v$_1$" if grp == "analytic" else "at t$_{end}$",
        "inf": "limit v \u2192 \u221e (eqs. 12-14)",
        "post_drop": "3/4 \u221a(d/R): right after a stop",
    }.get(when, when)
    if grp == "residuals":
        kind = {"pre": "numerical error", "jump": "numerical error",
                "post": "distance from the stationary state at v$_1$",
                "inf": "distance from the v \u2192 \u221e limit",
                "post_drop": "distance from 3/4 \u221a(d/R)"}.get(when, "")
        label = f"({SYMBOL[q]} \u2212 analytic) / |analytic|, {what}"
        return label, f"residual of {name}: {kind}"
    sym = (SCALED2 if v2 else SCALED)[q] if scaled else SYMBOL[q]
    unit = "" if scaled else UNIT[q]
    src = "analytic " if grp == "analytic" else ""
    label = f"{src}{sym} {what} {unit}".strip()
    return label, f"{src}{NAME[q]} {name}"


def colname(m, c):
    """Axis label of a grid axis or /cases column: the tool's own, else the
    meaning and unit the map's /schema gives, else the name."""
    if c in COLNAME:
        return COLNAME[c]
    for key in (f"grid/{c}", f"cases/{c}"):
        if key in m["schema"]:
            unit, meaning = m["schema"][key]
            return f"{c}: {meaning}" + (f" [{unit}]" if unit else "")
    return c


def scale_of(m, key):
    grp, q, _ = base_of(key)
    name = key.split("/", 1)[1]
    if m.get("version") == 2:
        if grp == "residuals":
            return None
        a = m["a"]
        if q == "mu" or name.startswith(("a_", "b_", "a_minus_b_")):
            return m["mu_scale"]
        if q in ("a2", "a1") or name.startswith(("d_c_", "slip_peak_")):
            return a
        if q == "d":
            return a * a / m["R"]
        if q in ("FN", "Fx"):
            return m["G"] * a ** 3 / m["R"]
        return None
    if grp == "residuals" or q not in SYMBOL:
        return None
    return {"FN": m["G"] * m["a1"] * m["d"], "Fx": m["G"] * m["d"] ** 2,
            "mu": (m["d"] / m["R"]) ** 0.5, "a2": m["a1"]}[q]


def parse_slices(specs, np):
    out = {}
    for spec in specs or []:
        if "=" not in spec:
            raise UserError(f"--slice {spec!r}: expected AXIS=VALUE, e.g. --slice R=1")
        k, v = (s.strip() for s in spec.split("=", 1))
        try:
            val = float(v)
        except ValueError:
            raise UserError(f"--slice {spec}: {v!r} is not a number") from None
        if not math.isfinite(val):
            raise UserError(f"--slice {spec}: {v!r} is not a finite number")
        out[k] = val
    return out


def nearest(values, target, log, np):
    values = np.asarray(values, dtype=float)
    if log and target > 0 and np.all(values > 0):
        return int(np.argmin(np.abs(np.log(values / target))))
    return int(np.argmin(np.abs(values - target)))


def axis_kind(values, flagged, np):
    """'log', 'linear' or 'category' for a grid axis."""
    v = np.asarray(values, dtype=float)
    if len(v) < 2:
        return "linear"
    if flagged and np.all(v > 0):
        return "log"
    d = np.diff(v)
    if np.all(v > 0) and v.max() / v.min() >= 10:
        r = np.diff(np.log(v))
        if np.all(r > 0) and np.ptp(r) <= 1e-6 * abs(r.mean()):
            return "log"
    if np.all(d > 0) and np.ptp(d) <= 1e-6 * abs(d.mean()):
        return "linear"
    return "category"


def coords(values, kind, np):
    """Plot coordinates of a grid axis: log10 of the values on a log axis, the index
    on a category axis, the values otherwise."""
    v = np.asarray(values, dtype=float)
    if kind == "category":
        return np.arange(len(v), dtype=float)
    return np.log10(v) if kind == "log" else v


def edges(c, np):
    """Cell edges around the plot coordinates c (midpoints, ends mirrored)."""
    if len(c) == 1:
        return np.array([c[0] - 0.5, c[0] + 0.5])
    mid = 0.5 * (c[1:] + c[:-1])
    return np.concatenate([[c[0] - (mid[0] - c[0])], mid, [c[-1] + (c[-1] - mid[-1])]])


# ----------------------------------------------------------------- plotting

def colour_setup(values, key, args, np, colors, plt):
    """(cmap, norm, notes) for the finite values shown."""
    grp = key.split("/", 1)[0]
    finite = values[np.isfinite(values)]
    notes = []
    if grp == "residuals" and not args.no_diverging:
        cmap = plt.get_cmap(args.cmap or "RdBu_r").copy()
        top = float(np.max(np.abs(finite))) if finite.size else 1.0
        if args.vmax is not None:
            top = abs(args.vmax)
        if top == 0:
            top = 1e-16
            notes.append("every value is exactly 0")
        if args.log_color:
            nz = np.abs(finite[finite != 0])
            lin = max(float(nz.min()) if nz.size else top * 1e-6, top * 1e-12)
            norm = colors.SymLogNorm(linthresh=lin, vmin=-top, vmax=top, base=10)
        else:
            norm = colors.Normalize(vmin=-top, vmax=top)
    else:
        cmap = plt.get_cmap(args.cmap or "viridis").copy()
        if args.log_color:
            pos = finite[finite > 0]
            if pos.size == 0:
                raise UserError(f"{key}: no positive value to show on a log colour scale "
                                f"(drop --log-color)")
            if pos.size < finite.size:
                notes.append(f"{finite.size - pos.size} value(s) <= 0 drawn grey (log colour scale)")
            lo = args.vmin if args.vmin is not None and args.vmin > 0 else float(pos.min())
            hi = args.vmax if args.vmax is not None else float(pos.max())
            if hi <= lo:
                hi = lo * 10
            norm = colors.LogNorm(vmin=lo, vmax=hi)
        else:
            lo = args.vmin if args.vmin is not None else (float(finite.min()) if finite.size else 0)
            hi = args.vmax if args.vmax is not None else (float(finite.max()) if finite.size else 1)
            if hi <= lo:
                hi = lo + (abs(lo) or 1.0)
            norm = colors.Normalize(vmin=lo, vmax=hi)
    cmap.set_bad("0.82")
    return cmap, norm, notes


def log_coords(values, np):
    """Coordinates for a scatter axis: (coords, kind, floor) where kind is 'log' or
    'linear'; in log kind coords are log10 values and zeros sit at `floor`."""
    v = np.asarray(values, dtype=float)
    pos = v[v > 0]
    if pos.size and np.all(v >= 0) and pos.max() / pos.min() >= 10:
        floor = float(math.floor(math.log10(pos.min())) - 1)
        c = np.full(v.shape, floor)
        c[v > 0] = np.log10(v[v > 0])
        return c, "log", floor if np.any(v == 0) else None
    return v, "linear", None


def decade_formatter(ticker, zero_at=None):
    """Tick labels for an axis in log10 coordinates (zero_at: where 0 is drawn)."""
    def f(val, _pos):
        if zero_at is not None and abs(val - zero_at) < 1e-9:
            return "0"
        if abs(val - round(val)) < 1e-9:
            k = int(round(val))
            return "1" if k == 0 else ("10" if k == 1 else f"$10^{{{k}}}$")
        return fmt(10 ** val)
    return ticker.FuncFormatter(f)


def log10_axis(axis, lo, hi, np, ticker, zero_at=None):
    """Decade ticks (and minor ticks at 2..9) on an axis drawn in log10 coordinates."""
    if hi - lo >= 1.5:
        axis.set_major_locator(ticker.MaxNLocator(integer=True, nbins=9))
        minor = [k + math.log10(j) for k in range(math.floor(lo), math.ceil(hi) + 1)
                 for j in range(2, 10)]
        axis.set_minor_locator(ticker.FixedLocator(minor))
    else:
        axis.set_major_locator(ticker.MaxNLocator(nbins=5))
    axis.set_major_formatter(decade_formatter(ticker, zero_at))


def label_spots(cs, yc, frac, np):
    """One label position per contour level, at the height frac of the y range."""
    y0 = float(yc.min()) + frac * float(np.ptp(yc))
    spots = []
    for segs in cs.allsegs:
        pts = [p for seg in segs for p in seg]
        if pts:
            pts = np.asarray(pts)
            spots.append(tuple(pts[int(np.argmin(np.abs(pts[:, 1] - y0)))]))
    return spots


def main(argv=None):
    ap = Parser(prog=PROG, description=__doc__,
                formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("map", help="mdrmap map (.h5)")
    ap.add_argument("quantity", nargs="*", default=None,
                    help="dataset(s) of /results, /analytic, /residuals (default: mu_jump)")
    ap.add_argument("-o", "--output", default=None,
                    help="PNG to write (default: <map name>_<quantity>.png in the current directory)")
    ap.add_argument("--x", default=None, metavar="AXIS", help="grid axis (or /cases column) on x")
    ap.add_argument("--y", default=None, metavar="AXIS", help="grid axis (or /cases column) on y")
    ap.add_argument("--slice", action="append", metavar="AXIS=VALUE",
                    help="take AXIS at the grid value nearest to VALUE (repeatable); in scatter "
                         "plots, keep only the cases at the nearest value")
    ap.add_argument("--log-color", action="store_true",
                    help="logarithmic colour scale (symmetric log for residuals)")
    ap.add_argument("--scaled", action="store_true",
                    help="divide by the similarity scales (G a1 d, G d^2, sqrt(d/R), a1)")
    ap.add_argument("--similarity", action="store_true",
                    help="plot over zeta = v tau/a1 and zeta1 = v1 tau/a1 (implies --scaled)")
    ap.add_argument("--contour", default=None, metavar="L1,L2,...",
                    help="contour lines of the plotted quantity at these levels (grid maps)")
    ap.add_argument("--zeta-lines", action="store_true",
                    help="dashed lines of constant zeta = v tau/a1 at whole decades (grid maps)")
    ap.add_argument("--vmin", type=float, default=None, help="colour scale minimum")
    ap.add_argument("--vmax", type=float, default=None, help="colour scale maximum")
    ap.add_argument("--cmap", default=None, help="matplotlib colour map (default viridis; RdBu_r "
                                                  "for residuals)")
    ap.add_argument("--no-diverging", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--title", default=None, help="figure title (default: map name and slices)")
    ap.add_argument("--dpi", type=int, default=120, help="resolution (default 120)")
    args = ap.parse_args(argv)
    if args.dpi <= 0 or args.dpi > 1200:
        raise UserError(f"--dpi {args.dpi}: must be in 1..1200")
    levels = None
    if args.contour:
        try:
            levels = sorted(float(s) for s in args.contour.split(",") if s.strip())
        except ValueError:
            raise UserError(f"--contour {args.contour!r}: expected numbers separated by commas") \
                from None
    slices_req = parse_slices(args.slice, None)

    import numpy as np
    import h5py

    m = load(args.map, np, h5py)
    quantities = args.quantity or (["mu_after_0"] if m["version"] == 2 else ["mu_jump"])
    keys = [resolve(m, q) for q in quantities]
    scaled = args.scaled or args.similarity
    if args.cmap:
        import matplotlib
        if args.cmap not in matplotlib.colormaps:
            raise UserError(f"--cmap {args.cmap!r}: not a matplotlib colour map")
    done = m["status"] == 1
    notes = []

    grid = m["grid"]
    mode = "similarity" if args.similarity else ("grid" if grid else "cases")
    plan = {"mode": mode}
    asked = {}
    if mode == "grid":
        axes = grid["axes"]
        # history aliases (mdrmap-map/2): v1_over_v is the axis w1_over_v, and back
        args.x = resolve_axis(args.x, axes) or args.x if args.x else None
        args.y = resolve_axis(args.y, axes) or args.y if args.y else None
        for k in list(slices_req):
            a = resolve_axis(k, axes)
            if a and a != k:
                slices_req[a] = slices_req.pop(k)
                asked[a] = k
        for name in (args.x, args.y):
            if name is not None and name not in axes:
                raise UserError(f"--x/--y {name!r}: not a grid axis (axes: {', '.join(axes)}; "
                                f"--similarity plots over zeta and zeta1)")
        if args.x is not None and args.x == args.y:
            raise UserError(f"--x and --y are both {args.x!r}")
        for k in slices_req:
            if k not in axes:
                raise UserError(f"--slice {k}=...: no grid axis {k!r} (axes: {', '.join(axes)})")
            if k in (args.x, args.y):
                raise UserError(f"--slice {k}=...: {k} is plotted on the "
                                f"{'x' if k == args.x else 'y'} axis")
        # most values first; on a tie the later (faster) axis, e.g. v before d, goes on x
        order = sorted(range(len(axes)), key=lambda i: (-grid["shape"][i], -i))
        free = [axes[i] for i in order if axes[i] not in slices_req and
                axes[i] not in (args.x, args.y)]
        multi = [a for a in free if grid["shape"][axes.index(a)] > 1]
        x = args.x or (multi.pop(0) if multi else None)
        y = args.y
        if y is None:
            cand = [a for a in multi if a != x]
            y = cand[0] if cand else None
        if x is None:
            raise UserError("the grid has no axis with more than one value to plot over "
                            "(use map_summary.py to see the values)")
        if x in slices_req or (y and y in slices_req):
            raise UserError("an axis cannot be both plotted and sliced")
        index = []
        slice_text = []
        for i, a in enumerate(axes):
            vals = grid["values"][i]
            kind = axis_kind(vals, grid["log"][i], np)
            if a in (x, y):
                index.append(slice(None))
                continue
            if a in slices_req:
                j = nearest(vals, slices_req[a], kind == "log", np)
                lo, hi = float(vals.min()), float(vals.max())
                msg = (f"slice {asked.get(a, a)}={fmt(slices_req[a])} -> {a}={fmt(vals[j])} "
                       f"(value {j + 1} of {len(vals)})")
                if not lo * (1 - 1e-12) <= slices_req[a] <= hi * (1 + 1e-12) and len(vals) > 1:
                    msg += f"; note: {fmt(slices_req[a])} is outside [{fmt(lo)}, {fmt(hi)}]"
                notes.append(msg)
            else:
                j = 0
                if len(vals) > 1:
                    notes.append(f"axis {a} not sliced: taking {a}={fmt(vals[0])} "
                                 f"(first of {len(vals)}; use --slice {a}=VALUE)")
            index.append(j)
            slice_text.append(f"{a}={fmt(vals[j])}")
        plan.update(x=x, y=y, index=tuple(index), slice_text=slice_text)
    else:
        cols = m["case_cols"] + m["derived"]
        if mode == "similarity":
            x, y = "zeta", "zeta1"
            if args.x or args.y:
                notes.append("--similarity: x is zeta and y is zeta1 (--x/--y ignored)")
        else:
            for name in (args.x, args.y):
                if name is not None and name not in cols:
                    raise UserError(f"--x/--y {name!r}: not a /cases column "
                                    f"(valid: {', '.join(cols)})")
            distinct = {c: len(np.unique(m[c][np.isfinite(m[c])])) for c in cols}
            order = sorted(m["case_cols"], key=lambda c: (-distinct[c], m["case_cols"].index(c)))
            x = args.x or next(c for c in order if c != args.y)
            y = args.y or next(c for c in order if c != x)
        sel = np.ones(m["n"], dtype=bool)
        slice_text = []
        for k, val in slices_req.items():
            if k not in cols:
                raise UserError(f"--slice {k}=...: no column {k!r} (valid: {', '.join(cols)})")
            u = np.unique(m[k][np.isfinite(m[k])])
            j = nearest(u, val, True, np)
            sel &= np.isclose(m[k], u[j], rtol=1e-12, atol=0)
            notes.append(f"slice {k}={fmt(val)} -> {k}={fmt(u[j])} ({int(sel.sum())} cases)")
            slice_text.append(f"{k}={fmt(u[j])}")
        plan.update(x=x, y=y, sel=sel, slice_text=slice_text)

    output = args.output or (os.path.splitext(os.path.basename(args.map))[0] + "_"
                             + "_".join(k.split("/", 1)[1] if k.startswith("results/")
                                        else k.replace("/", "-") for k in keys) + ".png")
    outdir = os.path.dirname(os.path.abspath(output))
    if not os.path.isdir(outdir):
        raise UserError(f"cannot write {output}: no such directory {outdir}")

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import colors, patheffects, ticker
    from matplotlib.tri import Triangulation

    npanel = len(keys)
    ncols = min(npanel, 3)
    nrows = math.ceil(npanel / ncols)
    fig, axs = plt.subplots(nrows, ncols, figsize=(5.9 * ncols, 4.9 * nrows + 0.5), squeeze=False)
    axs = axs.ravel()
    for ax in axs[npanel:]:
        ax.set_visible(False)

    # which cases are plotted, and how many of them are not done
    if mode == "grid":
        shape = grid["shape"]
        status_sel = m["status"].reshape(shape)[plan["index"]]
        in_plot = status_sel.size
        n_skip = int(np.sum(status_sel != 1))
        n_fail = int(np.sum(status_sel == -1))
    else:
        in_plot = int(plan["sel"].sum())
        n_skip = int(np.sum(plan["sel"] & ~done))
        n_fail = int(np.sum(plan["sel"] & (m["status"] == -1)))
    if n_skip:
        notes.append(f"skipped {n_skip} of {in_plot} cases in the plot: not done "
                     f"({n_fail} failed, {n_skip - n_fail} pending)")
    if in_plot - n_skip == 0:
        raise UserError(f"no done case to plot ({n_skip} of {in_plot} in the plot are "
                        f"failed or pending)")

    for ax, key in zip(axs, keys):
        label, short = describe(key, scaled, m["schema"], m["version"] == 2)
        vals = m["data"][key].copy()
        sc = scale_of(m, key) if scaled else None
        if sc is not None:
            with np.errstate(divide="ignore", invalid="ignore"):
                vals = vals / sc
        vals[~done] = np.nan
        panel_notes = []
        if mode == "grid":
            axes, shape = grid["axes"], grid["shape"]
            xi = axes.index(plan["x"])
            xv = grid["values"][xi]
            xkind = axis_kind(xv, grid["log"][xi], np)
            sub = vals.reshape(shape)[plan["index"]]
            if plan["y"] is None:  # line plot
                ax.plot(np.arange(len(xv)) if xkind == "category" else xv, sub, "o-",
                        color="tab:blue", ms=4)
                if xkind == "log":
                    ax.set_xscale("log")
                if args.log_color and np.all(sub[np.isfinite(sub)] > 0):
                    ax.set_yscale("log")
                if xkind == "category":
                    ax.set_xticks(np.arange(len(xv)), [fmt(v) for v in xv])
                ax.set_xlabel(colname(m, plan["x"]))
                ax.set_ylabel(label)
                ax.grid(True, alpha=0.3)
            else:
                yi = axes.index(plan["y"])
                yv = grid["values"][yi]
                ykind = axis_kind(yv, grid["log"][yi], np)
                if xi < yi:
                    sub = sub.T  # rows: y, columns: x
                z = np.ma.masked_invalid(sub)
                cmap, norm, cn = colour_setup(np.asarray(sub), key, args, np, colors, plt)
                panel_notes += cn
                if args.log_color and not isinstance(norm, colors.SymLogNorm):
                    z = np.ma.masked_where(~(np.asarray(sub) > 0), z)
                xc, yc = coords(xv, xkind, np), coords(yv, ykind, np)
                mesh = ax.pcolormesh(edges(xc, np), edges(yc, np), z, cmap=cmap, norm=norm,
                                     shading="flat")
                cb = fig.colorbar(mesh, ax=ax)
                cb.set_label(label, fontsize=9)
                if levels and min(len(xv), len(yv)) >= 2:
                    halo = [patheffects.withStroke(linewidth=3, foreground="black", alpha=0.5)]
                    cs = ax.contour(xc, yc, np.ma.masked_invalid(sub), levels=levels,
                                    colors="white", linewidths=1.4)
                    plt.setp(cs.collections, path_effects=halo)
                    for t in ax.clabel(cs, fmt=lambda v: fmt(v), fontsize=8, colors="black",
                                       manual=label_spots(cs, yc, 0.25, np)):
                        t.set_bbox(LABEL_BOX)
                if args.zeta_lines and min(len(xv), len(yv)) >= 2:
                    zeta = m["zeta"].reshape(shape)[plan["index"]]
                    if xi < yi:
                        zeta = zeta.T
                    with np.errstate(divide="ignore"):
                        lz = np.log10(zeta)
                    lz = np.ma.masked_invalid(lz)
                    if lz.count() and np.ptp(lz.compressed()) > 0:
                        lo, hi = float(lz.min()), float(lz.max())
                        zl = np.arange(math.floor(lo) + 1, math.ceil(hi))  # inside only
                        if len(zl) > 12:
                            zl = zl[:: math.ceil(len(zl) / 10)]
                        cs = ax.contour(xc, yc, lz, levels=zl, colors="0.1", linewidths=0.8,
                                        linestyles="--")
                        for t in ax.clabel(cs, fmt=lambda v: f"\u03b6=1e{int(round(v))}",
                                           fontsize=7, manual=label_spots(cs, yc, 0.8, np)):
                            t.set_bbox(LABEL_BOX)
                for axis, kind, v, c in [(ax.xaxis, xkind, xv, xc), (ax.yaxis, ykind, yv, yc)]:
                    if kind == "log":
                        e = edges(c, np)
                        log10_axis(axis, e[0], e[-1], np, ticker)
                    elif kind == "category":
                        axis.set_ticks(np.arange(len(v)), [fmt(t) for t in v])
                        if axis is ax.xaxis and len(v) > 6:
                            plt.setp(axis.get_ticklabels(), rotation=45, ha="right")
                ax.set_xlabel(colname(m, plan["x"])
                              + (" (categories)" if xkind == "category" else ""))
                ax.set_ylabel(colname(m, plan["y"])
                              + (" (categories)" if ykind == "category" else ""))
        else:
            base = plan["sel"]
            shown = base & done & np.isfinite(vals)
            if args.log_color and key.split("/")[0] != "residuals":
                nonpos = shown & ~(vals > 0)
                if np.any(nonpos):
                    panel_notes.append(f"{int(nonpos.sum())} case(s) <= 0 not shown (log colour)")
                shown &= vals > 0
            if not np.any(shown):
                raise UserError(f"{key}: no done case with a finite value to plot")
            # positions of every case of the selection (done or not), then the shown ones
            xs_all, xkind, xfloor = log_coords(m[plan["x"]][base], np)
            ys_all, ykind, yfloor = log_coords(m[plan["y"]][base], np)
            idx_all = np.flatnonzero(base)
            pick = shown[base]
            xs, ys, zs = xs_all[pick], ys_all[pick], vals[shown]
            cmap, norm, cn = colour_setup(zs, key, args, np, colors, plt)
            panel_notes += cn
            hollow = np.zeros(zs.shape, dtype=bool)
            if xfloor is not None:
                hollow |= xs == xfloor
            if yfloor is not None:
                hollow |= ys == yfloor
            notdone = ~done[base]
            if np.any(notdone):
                ax.scatter(xs_all[notdone], ys_all[notdone], marker="x", color="0.45", s=42,
                           linewidths=1.2, zorder=4)
                panel_notes.append(f"\u00d7: {int(notdone.sum())} case(s) not done")
            if mode == "cases" and idx_all.size <= 40:
                for i, xv_, yv_ in zip(idx_all, xs_all, ys_all):
                    ax.annotate(str(i), (xv_, yv_), xytext=(4, 3), textcoords="offset points",
                                fontsize=7, color="0.3")
            if mode == "similarity" and zs.size >= 4:
                # cases sharing (zeta, zeta1): the spread checks the similarity collapse
                keyxy = np.round(np.c_[xs, ys], 9)
                uniq, inv = np.unique(keyxy, axis=0, return_inverse=True)
                inv = np.ravel(inv)
                spread, groups = 0.0, 0
                for g in range(len(uniq)):
                    zz = zs[inv == g]
                    if zz.size > 1:
                        groups += 1
                        ref = max(np.max(np.abs(zz)), 1e-300)
                        spread = max(spread, float(np.ptp(zz) / ref))
                if groups:
                    notes.append(f"{key}: {groups} (zeta, zeta1) points shared by several cases; "
                                 f"largest relative spread {spread:.2e}")
                mean = np.array([zs[inv == g].mean() for g in range(len(uniq))])
                if len(uniq) >= 6 and np.ptp(uniq[:, 0]) > 0 and np.ptp(uniq[:, 1]) > 0:
                    try:
                        tri = Triangulation(uniq[:, 0], uniq[:, 1])
                        if isinstance(norm, colors.LogNorm):
                            lv = np.logspace(math.log10(norm.vmin), math.log10(norm.vmax), 15)
                        else:
                            lv = np.linspace(norm.vmin, norm.vmax, 15)
                        ax.tricontourf(tri, mean, levels=lv, cmap=cmap, norm=norm, alpha=0.55,
                                       extend="both")
                    except (ValueError, RuntimeError):
                        pass  # points on a line: the scatter alone
            sca = ax.scatter(xs[~hollow], ys[~hollow], c=zs[~hollow], cmap=cmap, norm=norm, s=36,
                             edgecolors="0.2", linewidths=0.4, zorder=3)
            if np.any(hollow):
                ax.scatter(xs[hollow], ys[hollow], facecolors="none",
                           edgecolors=cmap(norm(zs[hollow])), s=44, linewidths=1.4, zorder=3)
                which = " and ".join(n for n, fl in [(plan["x"], xfloor), (plan["y"], yfloor)]
                                     if fl is not None)
                panel_notes.append(f"hollow: {which} = 0 (tick '0' on the log axis)")
            cb = fig.colorbar(sca, ax=ax)
            cb.set_label(label, fontsize=9)
            for axis, kind, c, fl in [(ax.xaxis, xkind, xs_all, xfloor),
                                      (ax.yaxis, ykind, ys_all, yfloor)]:
                if kind == "log":
                    log10_axis(axis, float(c.min()), float(c.max()), np, ticker, zero_at=fl)
            ax.set_xlabel(colname(m, plan["x"]))
            ax.set_ylabel(colname(m, plan["y"]))
            ax.grid(True, alpha=0.25)
        title = short
        if scaled and scale_of(m, key) is not None:
            title += " (scaled)"
        if panel_notes:
            title += "\n" + "; ".join(panel_notes)
        ax.set_title(title, fontsize=10 if not panel_notes else 9)

    head = args.title
    if head is None:
        head = f"{os.path.basename(args.map)}: " + ", ".join(k.split("/", 1)[1] if k.startswith(
            "results/") else k for k in keys)
        if mode == "similarity":
            head += " over the similarity variables"
    subtitle = []
    if plan["slice_text"]:
        subtitle.append("at " + ", ".join(plan["slice_text"]))
    if n_skip:
        subtitle.append(f"{n_skip} case{'s' if n_skip != 1 else ''} not done (drawn grey, "
                        f"{'cells' if mode == 'grid' else 'crosses'})")
    fig.suptitle(head + ("\n" + "; ".join(subtitle) if subtitle else ""), fontsize=11)
    fig.tight_layout(rect=(0, 0.02, 1, 0.97))
    for note in notes:
        print(f"{PROG}: {note}")
    save_figure(fig, output, args.dpi)
    print(f"{PROG}: wrote {output}")
    return 0



if __name__ == "__main__":
    sys.exit(run_tool(main, PROG))
