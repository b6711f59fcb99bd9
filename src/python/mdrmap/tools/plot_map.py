# pyrun-needs: numpy matplotlib h5py
"""Colour map of one or more quantities of an mdrmap map over two parameters.

QUANTITY is a dataset of /results, /events, /analytic or /residuals of an
mdrmap-map/2 map (docs/reference/map-schema.md); per-event datasets ([N, K]: /events,
analytic/<q>_ss, residuals/<q>_end) are quantities <name>_<k> for event k,
e.g. `mu_after_0` (the friction just after the change at t = 0: the
default), `mu_peak_1`, `a_0`, `d_c_0`, `analytic/mu_ss_0`,
`residuals/mu_end_0`; bare names are looked up in /results, /events,
/analytic, /residuals, in that order, a prefixed one (`analytic/mu_pre`)
names its group. Several quantities give one panel each. Labels, units and
meanings come from the map's /schema; undefined values (the fill value) are
drawn grey like cases not done. The grid's axes include the history's
(w1_over_v, T1_over_tau, ...); `--slice v1_over_v=...` finds w1_over_v.

`--scaled` divides each quantity by the map's scale for its /schema unit
(/scales: lengths by the length scale a, a1 at depth or the Hertz radius a0
under load, depths by the depth scale, forces by the force scale, times by
the time scale, friction coefficients and a, b, a - b by the friction scale
a/R); `--similarity` plots over zeta = v tau / a and zeta1 = w1 tau / a (v
and w1 times /scales/time over /scales/length) and implies --scaled.

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

`--similarity` draws a scatter (and filled contours where the points span an
area) and prints how far cases sharing (zeta, zeta1) differ, which checks the
collapse. Maps written from a [cases] list (no /grid) are drawn as a scatter
over two /cases columns (default: the two with the most distinct values).
Residuals use a symmetric diverging colour map. Cases that are pending or
failed are drawn grey (not-done) and counted.

Usage:
    python3 -m mdrmap plot_map MAP.h5 -o map.png
    python3 -m mdrmap plot_map MAP.h5 mu_pre mu_after_0 --x v --y d --log-color -o mu.png
    python3 -m mdrmap plot_map MAP.h5 residuals/mu_pre --slice R=1 -o res.png
    python3 -m mdrmap plot_map MAP.h5 mu_after_0 --similarity -o sim.png

Exit codes: 0 success, 2 bad input (one line on stderr).
"""

import argparse
import math
import os
import sys
import textwrap

from ._maplib import (Parser, UserError, load_cases, open_map, read_masked, resolve_axis,
                    run_tool, save_figure, scale_of, scale_symbol)

PROG = "plot_map"
GROUPS = ["results", "events", "analytic", "residuals"]  # the order bare names are looked up
DERIVED = ["zeta", "zeta1"]
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

def load(path, np, h5py):
    """The map in the form the plots read: its cases (load_cases) with every
    /cases column and wk, Tk as m[name], zeta and zeta1 (from /scales), and
    the numeric per-case datasets of GROUPS as m["data"]["<group>/<name>"]
    (per-event ones as <group>/<name>_<k>)."""
    with open_map(path, h5py, PROG) as f:
        c = load_cases(f, path, np)
        n, K = c["n"], c["K"]
        m = dict(c, data={})
        m["case_cols"] = list(c["cols"]) + [f"{kind}{j + 1}" for j in range(K) for kind in "wT"]
        m.update(c["cols"])
        for j in range(K):
            m[f"w{j + 1}"], m[f"T{j + 1}"] = c["w"][:, j], c["T"][:, j]
        with np.errstate(divide="ignore", invalid="ignore"):
            m["zeta1"] = c["w"][:, 0] * c["scales"]["time"] / c["a"]
        m["derived"] = DERIVED
        for grp in GROUPS:
            for name, ds in (f[grp].items() if grp in f else []):
                if not hasattr(ds, "dtype") or ds.dtype.kind not in "fiu":
                    continue
                if ds.shape == (n,):
                    m["data"][f"{grp}/{name}"] = read_masked(ds).astype(float)
                elif len(ds.shape) == 2 and ds.shape[0] == n:
                    x = read_masked(ds).astype(float)
                    for j in range(ds.shape[1]):
                        m["data"][f"{grp}/{name}_{j}"] = x[:, j]
    if m["grid"]:
        m["grid"] = dict(m["grid"], log=[bool(k) for k in m["grid"]["log"]])
    return m


def resolve(m, name):
    key = name.strip().strip("/")
    if "/" in key:
        if key in m["data"]:
            return key
    else:
        for grp in GROUPS:
            if f"{grp}/{key}" in m["data"]:
                return f"{grp}/{key}"
    bare = sorted({k.split("/", 1)[1] for k in m["data"]})
    raise UserError(f"unknown quantity {name!r}; valid: {', '.join(bare)} (bare names come "
                    f"from /results, /events, then /analytic; <name>_<k> is event k; prefix "
                    f"analytic/ or residuals/ for those groups, e.g. residuals/mu_end_0)")


def schema_entry(m, key):
    """(unit, meaning) of a dataset "group/name" or a per-event "group/name_<k>"."""
    entry = m["schema"].get(key)
    grp, name = key.split("/", 1)
    if entry is None and name.rsplit("_", 1)[-1].isdigit():
        entry = m["schema"].get(f"{grp}/{name.rsplit('_', 1)[0]}")
    return entry or ("", "")


def describe(m, key, scaled):
    """(colour bar label, panel title) of a dataset: its name with its /schema
    unit (or, scaled, the symbol of its /scales entry), and its meaning."""
    name = key.split("/", 1)[1]
    unit, meaning = schema_entry(m, key)
    sc = scale_of(m, key) if scaled else None
    prefix = "" if key.startswith(("results/", "events/")) else key.split("/", 1)[0] + "/"
    if sc:
        label = f"{prefix}{name} / {scale_symbol(m, sc)}"
    else:
        label = f"{prefix}{name}" + (f" [{unit}]" if unit and unit != "number" else "")
    title = textwrap.shorten(f"{name}: {meaning}", 90, placeholder=" ...") if meaning else name
    return label, "\n".join(textwrap.wrap(title, 55))


def colname(m, c):
    """Axis label of a grid axis or /cases column from the map's /schema (zeta
    and zeta1 from the scales they are made of)."""
    if c in DERIVED:
        v = "v" if c == "zeta" else "w$_1$"
        return f"{c} = {v} \u03c4 / {m['a_name']}  (/scales: time over length)"
    for key in (f"grid/{c}", f"cases/{c}"):
        if key in m["schema"]:
            unit, meaning = m["schema"][key]
            unit = f" [{unit}]" if unit and unit != "number" else ""
            return textwrap.shorten(f"{c}: {meaning}", 44 - len(unit), placeholder=" ...") + unit
    return c


def scale_values(m, key):
    """The values a dataset is divided by with --scaled (its /scales entry), or None."""
    sc = scale_of(m, key)
    return None if sc is None else m["scales"][sc]


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


def build_parser():
    ap = Parser(prog=PROG, description=__doc__,
                formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("map", help="mdrmap map (.h5)")
    ap.add_argument("quantity", nargs="*", default=None,
                    help="dataset(s) of /results, /events, /analytic, /residuals (default: "
                         "mu_after_0)")
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
                    help="divide by the map's /scales (length, depth, force, friction, time)")
    ap.add_argument("--similarity", action="store_true",
                    help="plot over zeta = v tau/a and zeta1 = w1 tau/a (implies --scaled)")
    ap.add_argument("--contour", default=None, metavar="L1,L2,...",
                    help="contour lines of the plotted quantity at these levels (grid maps)")
    ap.add_argument("--zeta-lines", action="store_true",
                    help="dashed lines of constant zeta = v tau/a at whole decades (grid maps)")
    ap.add_argument("--vmin", type=float, default=None, help="colour scale minimum")
    ap.add_argument("--vmax", type=float, default=None, help="colour scale maximum")
    ap.add_argument("--cmap", default=None, help="matplotlib colour map (default viridis; RdBu_r "
                                                  "for residuals)")
    ap.add_argument("--no-diverging", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--title", default=None, help="figure title (default: map name and slices)")
    ap.add_argument("--dpi", type=int, default=120, help="resolution (default 120)")
    return ap


def check_args(args):
    """The contour levels; UserError for a bad --dpi, --contour or --cmap."""
    if args.dpi <= 0 or args.dpi > 1200:
        raise UserError(f"--dpi {args.dpi}: must be in 1..1200")
    if args.cmap:
        import matplotlib
        if args.cmap not in matplotlib.colormaps:
            raise UserError(f"--cmap {args.cmap!r}: not a matplotlib colour map")
    if not args.contour:
        return None
    try:
        return sorted(float(s) for s in args.contour.split(",") if s.strip())
    except ValueError:
        raise UserError(f"--contour {args.contour!r}: expected numbers separated by commas") \
            from None


def grid_xy(args, grid, slices_req):
    """The two plotted grid axes (y None for a line plot)."""
    axes = grid["axes"]
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
    free = [axes[i] for i in order if axes[i] not in slices_req and axes[i] not in (args.x, args.y)]
    multi = [a for a in free if grid["shape"][axes.index(a)] > 1]
    x = args.x or (multi.pop(0) if multi else None)
    y = args.y
    if y is None:
        cand = [a for a in multi if a != x]
        y = cand[0] if cand else None
    if x is None:
        raise UserError("the grid has no axis with more than one value to plot over "
                        "(use map_summary.py to see the values)")
    return x, y


def plan_grid(args, grid, slices_req, notes, np):
    """The plot over two grid axes: {"mode", "x", "y", "index", "slice_text"}."""
    axes = grid["axes"]
    asked = {}
    # history aliases: v1_over_v is the axis w1_over_v, and back
    args.x = resolve_axis(args.x, axes) or args.x if args.x else None
    args.y = resolve_axis(args.y, axes) or args.y if args.y else None
    for k in list(slices_req):
        a = resolve_axis(k, axes)
        if a and a != k:
            slices_req[a] = slices_req.pop(k)
            asked[a] = k
    x, y = grid_xy(args, grid, slices_req)
    index, slice_text = [], []
    for i, a in enumerate(axes):
        vals = grid["values"][i]
        if a in (x, y):
            index.append(slice(None))
            continue
        j = 0
        if a in slices_req:
            j = nearest(vals, slices_req[a], axis_kind(vals, grid["log"][i], np) == "log", np)
            lo, hi = float(vals.min()), float(vals.max())
            msg = (f"slice {asked.get(a, a)}={fmt(slices_req[a])} -> {a}={fmt(vals[j])} "
                   f"(value {j + 1} of {len(vals)})")
            if not lo * (1 - 1e-12) <= slices_req[a] <= hi * (1 + 1e-12) and len(vals) > 1:
                msg += f"; note: {fmt(slices_req[a])} is outside [{fmt(lo)}, {fmt(hi)}]"
            notes.append(msg)
        elif len(vals) > 1:
            notes.append(f"axis {a} not sliced: taking {a}={fmt(vals[0])} "
                         f"(first of {len(vals)}; use --slice {a}=VALUE)")
        index.append(j)
        slice_text.append(f"{a}={fmt(vals[j])}")
    return {"mode": "grid", "x": x, "y": y, "index": tuple(index), "slice_text": slice_text}


def plan_cases(args, m, slices_req, notes, np):
    """A scatter over two /cases columns (or zeta, zeta1 with --similarity)."""
    cols = m["case_cols"] + m["derived"]
    if args.similarity:
        x, y = "zeta", "zeta1"
        if args.x or args.y:
            notes.append("--similarity: x is zeta and y is zeta1 (--x/--y ignored)")
    else:
        for name in (args.x, args.y):
            if name is not None and name not in cols:
                raise UserError(f"--x/--y {name!r}: not a /cases column (valid: {', '.join(cols)})")
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
    return {"mode": "similarity" if args.similarity else "cases", "x": x, "y": y, "sel": sel,
            "slice_text": slice_text}


def count_not_done(m, plan, notes, np):
    """How many plotted cases are not done (noted; UserError when none is done)."""
    if plan["mode"] == "grid":
        status = m["status"].reshape(m["grid"]["shape"])[plan["index"]]
        in_plot, n_skip, n_fail = status.size, int(np.sum(status != 1)), int(np.sum(status == -1))
    else:
        sel = plan["sel"]
        in_plot = int(sel.sum())
        n_skip = int(np.sum(sel & (m["status"] != 1)))
        n_fail = int(np.sum(sel & (m["status"] == -1)))
    if n_skip:
        notes.append(f"skipped {n_skip} of {in_plot} cases in the plot: not done "
                     f"({n_fail} failed, {n_skip - n_fail} pending)")
    if in_plot - n_skip == 0:
        raise UserError(f"no done case to plot ({n_skip} of {in_plot} in the plot are "
                        f"failed or pending)")
    return n_skip


def default_output(args, keys):
    output = args.output or (os.path.splitext(os.path.basename(args.map))[0] + "_"
                             + "_".join(k.split("/", 1)[1] if k.startswith("results/")
                                        else k.replace("/", "-") for k in keys) + ".png")
    outdir = os.path.dirname(os.path.abspath(output))
    if not os.path.isdir(outdir):
        raise UserError(f"cannot write {output}: no such directory {outdir}")
    return output


def draw_contours(ax, plt, patheffects, sub, xc, yc, levels, np):
    halo = [patheffects.withStroke(linewidth=3, foreground="black", alpha=0.5)]
    cs = ax.contour(xc, yc, np.ma.masked_invalid(sub), levels=levels, colors="white",
                    linewidths=1.4)
    plt.setp(cs.collections, path_effects=halo)
    for t in ax.clabel(cs, fmt=lambda v: fmt(v), fontsize=8, colors="black",
                       manual=label_spots(cs, yc, 0.25, np)):
        t.set_bbox(LABEL_BOX)


def draw_zeta_lines(ax, zeta, xc, yc, np):
    """Dashed lines of constant zeta (the map's scales) at whole decades."""
    with np.errstate(divide="ignore"):
        lz = np.ma.masked_invalid(np.log10(zeta))
    if not lz.count() or np.ptp(lz.compressed()) <= 0:
        return
    zl = np.arange(math.floor(float(lz.min())) + 1, math.ceil(float(lz.max())))  # inside only
    if len(zl) > 12:
        zl = zl[:: math.ceil(len(zl) / 10)]
    cs = ax.contour(xc, yc, lz, levels=zl, colors="0.1", linewidths=0.8, linestyles="--")
    for t in ax.clabel(cs, fmt=lambda v: f"\u03b6=1e{int(round(v))}", fontsize=7,
                       manual=label_spots(cs, yc, 0.8, np)):
        t.set_bbox(LABEL_BOX)


def line_panel(ax, m, plan, sub, xv, xkind, label, args, np):
    ax.plot(np.arange(len(xv)) if xkind == "category" else xv, sub, "o-", color="tab:blue", ms=4)
    if xkind == "log":
        ax.set_xscale("log")
    if args.log_color and np.all(sub[np.isfinite(sub)] > 0):
        ax.set_yscale("log")
    if xkind == "category":
        ax.set_xticks(np.arange(len(xv)), [fmt(v) for v in xv])
    ax.set_xlabel(colname(m, plan["x"]))
    ax.set_ylabel(label)
    ax.grid(True, alpha=0.3)


def grid_panel(ax, fig, mpl, m, plan, key, vals, label, args, levels, np):
    """One quantity over the grid's two plotted axes (a line over one); the notes."""
    plt, colors, patheffects, ticker = mpl
    grid = m["grid"]
    axes, shape = grid["axes"], grid["shape"]
    xi = axes.index(plan["x"])
    xv = grid["values"][xi]
    xkind = axis_kind(xv, grid["log"][xi], np)
    sub = vals.reshape(shape)[plan["index"]]
    if plan["y"] is None:
        line_panel(ax, m, plan, sub, xv, xkind, label, args, np)
        return []
    yi = axes.index(plan["y"])
    yv = grid["values"][yi]
    ykind = axis_kind(yv, grid["log"][yi], np)
    if xi < yi:
        sub = sub.T  # rows: y, columns: x
    z = np.ma.masked_invalid(sub)
    cmap, norm, notes = colour_setup(np.asarray(sub), key, args, np, colors, plt)
    if args.log_color and not isinstance(norm, colors.SymLogNorm):
        z = np.ma.masked_where(~(np.asarray(sub) > 0), z)
    xc, yc = coords(xv, xkind, np), coords(yv, ykind, np)
    mesh = ax.pcolormesh(edges(xc, np), edges(yc, np), z, cmap=cmap, norm=norm, shading="flat")
    fig.colorbar(mesh, ax=ax).set_label(label, fontsize=9)
    if levels and min(len(xv), len(yv)) >= 2:
        draw_contours(ax, plt, patheffects, sub, xc, yc, levels, np)
    if args.zeta_lines and min(len(xv), len(yv)) >= 2:
        zeta = m["zeta"].reshape(shape)[plan["index"]]
        draw_zeta_lines(ax, zeta.T if xi < yi else zeta, xc, yc, np)
    for axis, kind, v, c in [(ax.xaxis, xkind, xv, xc), (ax.yaxis, ykind, yv, yc)]:
        if kind == "log":
            e = edges(c, np)
            log10_axis(axis, e[0], e[-1], np, ticker)
        elif kind == "category":
            axis.set_ticks(np.arange(len(v)), [fmt(t) for t in v])
            if axis is ax.xaxis and len(v) > 6:
                plt.setp(axis.get_ticklabels(), rotation=45, ha="right")
    ax.set_xlabel(colname(m, plan["x"]) + (" (categories)" if xkind == "category" else ""))
    ax.set_ylabel(colname(m, plan["y"]) + (" (categories)" if ykind == "category" else ""))
    return notes


def similarity_spread(ax, xs, ys, zs, key, cmap, norm, colors, notes, np):
    """Cases sharing (zeta, zeta1): their spread checks the similarity collapse;
    filled contours of the means where the points span an area."""
    from matplotlib.tri import Triangulation

    uniq, inv = np.unique(np.round(np.c_[xs, ys], 9), axis=0, return_inverse=True)
    inv = np.ravel(inv)
    spread, groups = 0.0, 0
    for g in range(len(uniq)):
        zz = zs[inv == g]
        if zz.size > 1:
            groups += 1
            spread = max(spread, float(np.ptp(zz) / max(np.max(np.abs(zz)), 1e-300)))
    if groups:
        notes.append(f"{key}: {groups} (zeta, zeta1) points shared by several cases; "
                     f"largest relative spread {spread:.2e}")
    mean = np.array([zs[inv == g].mean() for g in range(len(uniq))])
    if len(uniq) >= 6 and np.ptp(uniq[:, 0]) > 0 and np.ptp(uniq[:, 1]) > 0:
        try:
            if isinstance(norm, colors.LogNorm):
                lv = np.logspace(math.log10(norm.vmin), math.log10(norm.vmax), 15)
            else:
                lv = np.linspace(norm.vmin, norm.vmax, 15)
            ax.tricontourf(Triangulation(uniq[:, 0], uniq[:, 1]), mean, levels=lv, cmap=cmap,
                           norm=norm, alpha=0.55, extend="both")
        except (ValueError, RuntimeError):
            pass  # points on a line: the scatter alone


def shown_cases(base, vals, key, args, m, notes, np):
    shown = base & (m["status"] == 1) & np.isfinite(vals)
    if args.log_color and key.split("/")[0] != "residuals":
        nonpos = shown & ~(vals > 0)
        if np.any(nonpos):
            notes.append(f"{int(nonpos.sum())} case(s) <= 0 not shown (log colour)")
        shown &= vals > 0
    if not np.any(shown):
        raise UserError(f"{key}: no done case with a finite value to plot")
    return shown


def scatter_panel(ax, fig, mpl, m, plan, key, vals, label, args, notes, np):
    """One quantity as a scatter over two /cases columns (or zeta, zeta1); the notes."""
    plt, colors, _, ticker = mpl
    base, panel_notes = plan["sel"], []
    shown = shown_cases(base, vals, key, args, m, panel_notes, np)
    # positions of every case of the selection (done or not), then the shown ones
    xs_all, xkind, xfloor = log_coords(m[plan["x"]][base], np)
    ys_all, ykind, yfloor = log_coords(m[plan["y"]][base], np)
    idx_all, pick = np.flatnonzero(base), shown[base]
    xs, ys, zs = xs_all[pick], ys_all[pick], vals[shown]
    cmap, norm, cn = colour_setup(zs, key, args, np, colors, plt)
    panel_notes += cn
    hollow = np.zeros(zs.shape, dtype=bool)
    hollow |= (xs == xfloor) if xfloor is not None else hollow
    hollow |= (ys == yfloor) if yfloor is not None else hollow
    notdone = m["status"][base] != 1
    if np.any(notdone):
        ax.scatter(xs_all[notdone], ys_all[notdone], marker="x", color="0.45", s=42,
                   linewidths=1.2, zorder=4)
        panel_notes.append(f"\u00d7: {int(notdone.sum())} case(s) not done")
    if plan["mode"] == "cases" and idx_all.size <= 40:
        for i, xv_, yv_ in zip(idx_all, xs_all, ys_all):
            ax.annotate(str(i), (xv_, yv_), xytext=(4, 3), textcoords="offset points",
                        fontsize=7, color="0.3")
    if plan["mode"] == "similarity" and zs.size >= 4:
        similarity_spread(ax, xs, ys, zs, key, cmap, norm, colors, notes, np)
    sca = ax.scatter(xs[~hollow], ys[~hollow], c=zs[~hollow], cmap=cmap, norm=norm, s=36,
                     edgecolors="0.2", linewidths=0.4, zorder=3)
    if np.any(hollow):
        ax.scatter(xs[hollow], ys[hollow], facecolors="none",
                   edgecolors=cmap(norm(zs[hollow])), s=44, linewidths=1.4, zorder=3)
        which = " and ".join(n for n, fl in [(plan["x"], xfloor), (plan["y"], yfloor)]
                             if fl is not None)
        panel_notes.append(f"hollow: {which} = 0 (tick '0' on the log axis)")
    fig.colorbar(sca, ax=ax).set_label(label, fontsize=9)
    for axis, kind, c, fl in [(ax.xaxis, xkind, xs_all, xfloor), (ax.yaxis, ykind, ys_all, yfloor)]:
        if kind == "log":
            log10_axis(axis, float(c.min()), float(c.max()), np, ticker, zero_at=fl)
    ax.set_xlabel(colname(m, plan["x"]))
    ax.set_ylabel(colname(m, plan["y"]))
    ax.grid(True, alpha=0.25)
    return panel_notes


def figure(m, plan, keys, args, levels, notes, n_skip, np):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import colors, patheffects, ticker

    mpl = (plt, colors, patheffects, ticker)
    scaled = args.scaled or args.similarity
    ncols = min(len(keys), 3)
    nrows = math.ceil(len(keys) / ncols)
    fig, axs = plt.subplots(nrows, ncols, figsize=(5.9 * ncols, 4.9 * nrows + 0.5), squeeze=False)
    axs = axs.ravel()
    for ax in axs[len(keys):]:
        ax.set_visible(False)
    for ax, key in zip(axs, keys):
        label, title = describe(m, key, scaled)
        vals = m["data"][key].copy()
        sc = scale_values(m, key) if scaled else None
        if sc is not None:
            with np.errstate(divide="ignore", invalid="ignore"):
                vals = vals / sc
        vals[m["status"] != 1] = np.nan
        if plan["mode"] == "grid":
            panel_notes = grid_panel(ax, fig, mpl, m, plan, key, vals, label, args, levels, np)
        else:
            panel_notes = scatter_panel(ax, fig, mpl, m, plan, key, vals, label, args, notes, np)
        title += " (scaled)" if sc is not None else ""
        if panel_notes:
            title += "\n" + "; ".join(panel_notes)
        ax.set_title(title, fontsize=10 if not panel_notes else 9)
    head = args.title or (f"{os.path.basename(args.map)}: " + ", ".join(
        k.split("/", 1)[1] if k.startswith("results/") else k for k in keys)
        + (" over the similarity variables" if plan["mode"] == "similarity" else ""))
    subtitle = ["at " + ", ".join(plan["slice_text"])] if plan["slice_text"] else []
    if n_skip:
        subtitle.append(f"{n_skip} case{'s' if n_skip != 1 else ''} not done (drawn grey, "
                        f"{'cells' if plan['mode'] == 'grid' else 'crosses'})")
    fig.suptitle(head + ("\n" + "; ".join(subtitle) if subtitle else ""), fontsize=11)
    fig.tight_layout(rect=(0, 0.02, 1, 0.97))
    return fig


def main(argv=None):
    args = build_parser().parse_args(argv)
    levels = check_args(args)
    slices_req = parse_slices(args.slice, None)

    import numpy as np
    import h5py

    m = load(args.map, np, h5py)
    keys = [resolve(m, q) for q in (args.quantity or ["mu_after_0"])]
    notes = []
    if m["grid"] and not args.similarity:
        plan = plan_grid(args, m["grid"], slices_req, notes, np)
    else:
        plan = plan_cases(args, m, slices_req, notes, np)
    output = default_output(args, keys)
    n_skip = count_not_done(m, plan, notes, np)
    fig = figure(m, plan, keys, args, levels, notes, n_skip, np)
    for note in notes:
        print(f"{PROG}: {note}")
    save_figure(fig, output, args.dpi)
    print(f"{PROG}: wrote {output}")
    return 0


if __name__ == "__main__":
    sys.exit(run_tool(main, PROG))
