#!/usr/bin/env python3
# pyrun-needs: numpy matplotlib h5py
"""Maps of the apparent rate-and-state parameters of one event of an
mdrmap-map/2 grid study over two of its grid axes.

Four panels for event K (default 0: the change at t = 0 from v to w1; event k
is the change at the start of segment k + 1): the direct effect a, the
evolution b, a - b (events/a, b, a_minus_b; docs/design.md "Event metrics"),
in units of the friction scale a0/R under load (a0 = (3 FN R / (16 G))^(1/3))
or a1/R at fixed depth (a1 = sqrt(R d)), and D_c (events/d_c) in units of a0
or a1. `--unscaled` plots the map's values as they are. Colours of a, b and
a - b are symmetric about 0 (blue < 0 < red).

`--x AXIS --y AXIS` name the two grid axes (default: the two with the most
values, the longer on x); an axis is drawn logarithmically when /grid marks it
so (attribute `log`) or its values are geometric. Every other grid axis with
more than one value must be fixed with `--select AXIS=VALUE` (the grid value
nearest to VALUE is taken, and the tool says which) unless it has one value.
Undefined values (the fill value: a hold, equal velocities, a deviation that
does not decay to 1/e within the segment) are drawn blank (white) and counted,
and so are cases not done.

Prints a table per panel: how many cells are defined, undefined and not done,
and the minimum, median and maximum of the defined ones.

Usage:
    tools/pyrun tools/map_rate_state.py load_sweep.h5 --x v --y FN -o rate_state.png
    tools/pyrun tools/map_rate_state.py velocity_steps.h5 --event 1 --x v -o rs.png
    tools/pyrun tools/map_rate_state.py seed_step.h5 --x v --y w1_over_v --select tau=2 -o rs.png

Exit codes: 0 success, 2 bad input (one line on stderr).
"""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from maplib import (UserError, add_figure_options, add_select_option, fmt,  # noqa: E402
                    grid_index, map_tool_parser, nearest_index, open_map2, parse_map_tool_args,
                    read_masked, resolve_axis, run_tool, save_figure)

PROG = "map_rate_state"
METRICS = [("a", "direct effect a"), ("b", "evolution b"), ("a_minus_b", "a \u2212 b"),
           ("d_c", "D$_c$")]


def axis_is_log(values, flagged, np):
    v = np.asarray(values, dtype=float)
    if len(v) < 2 or not np.all(v > 0):
        return False
    if flagged:
        return True
    r = np.diff(np.log(v))
    return bool(v.max() / v.min() >= 10 and np.all(r > 0) and np.ptp(r) <= 1e-6 * abs(r.mean()))


def axis_kind(values, flagged, np):
    """'log', 'linear' or 'category' (neither evenly nor geometrically spaced)."""
    if axis_is_log(values, flagged, np):
        return "log"
    v = np.asarray(values, dtype=float)
    d = np.diff(v)
    if len(v) < 3 or (np.all(d > 0) and np.ptp(d) <= 1e-6 * abs(d.mean())):
        return "linear"
    return "category"


def coords(values, kind, np):
    v = np.asarray(values, dtype=float)
    return {"log": np.log10, "category": lambda u: np.arange(len(u), dtype=float)}.get(
        kind, lambda u: u)(v)


def edges(c, np):
    """Cell edges around the plot coordinates c (midpoints, ends mirrored)."""
    if len(c) == 1:
        return np.array([c[0] - 0.5, c[0] + 0.5])
    mid = 0.5 * (c[1:] + c[:-1])
    return np.concatenate([[c[0] - (mid[0] - c[0])], mid, [c[-1] + (c[-1] - mid[-1])]])


def main(argv=None):
    ap = map_tool_parser(PROG, __doc__, "mdrmap-map/2 map (.h5) of a grid study",
                         "_rate_state.png")
    ap.add_argument("--event", type=int, default=0, metavar="K",
                    help="0-based event: the change at the start of segment K+1 (default 0)")
    ap.add_argument("--x", default=None, metavar="AXIS", help="grid axis on x")
    ap.add_argument("--y", default=None, metavar="AXIS", help="grid axis on y")
    add_select_option(ap, "fix another grid axis at its value nearest to VALUE (repeatable)")
    ap.add_argument("--unscaled", action="store_true",
                    help="plot a, b, a-b and D_c as stored (no division by a/R and a)")
    add_figure_options(ap)
    args, sel, output = parse_map_tool_args(ap, argv)

    import numpy as np

    f, m = open_map2(args.map, np, PROG)
    with f:
        K = m["K"]
        if not 0 <= args.event < K:
            raise UserError(f"--event {args.event}: the map has {K} event(s) (0..{K - 1})")
        data = {}
        for name, _ in METRICS:
            if f"events/{name}" not in f:
                raise UserError(f"{args.map} is an incomplete mdrmap map (no /events/{name})")
            data[name] = read_masked(f[f"events/{name}"]).reshape(m["n"], K)[:, args.event]
    g = m["grid"]
    if g is None:
        raise UserError(f"{args.map} is a [cases] map (no /grid): this tool maps a grid study "
                        f"over two grid axes")
    axes, shape = g["axes"], g["shape"]
    x = y = None
    for opt, name in (("--x", args.x), ("--y", args.y)):
        if name is not None and resolve_axis(name, axes) is None:
            raise UserError(f"{opt} {name}: not a grid axis (axes: {', '.join(axes)})")
    x = resolve_axis(args.x, axes) if args.x else None
    y = resolve_axis(args.y, axes) if args.y else None
    if x is not None and x == y:
        raise UserError(f"--x and --y are both {x!r}")
    fixed = {}
    for name, val in sel.items():
        a = resolve_axis(name, axes)
        if a is None:
            raise UserError(f"--select {name}={fmt(val)}: no grid axis {name!r} "
                            f"(axes: {', '.join(axes)})")
        if a in (x, y):
            raise UserError(f"--select {name}=...: {a} is plotted on the {'x' if a == x else 'y'} axis")
        fixed[a] = val
    order = sorted(range(len(axes)), key=lambda i: (-shape[i], -i))
    free = [axes[i] for i in order if shape[i] > 1 and axes[i] not in fixed and axes[i] not in (x, y)]
    if x is None:
        if not free:
            raise UserError(f"{args.map}: no grid axis with more than one value to plot over "
                            f"(axes: {', '.join(axes)})")
        x = free.pop(0)
    if y is None and free:
        y = free.pop(0)
    notes = []
    if free:
        raise UserError(f"grid axis {free[0]} has {shape[axes.index(free[0])]} values: plot it "
                        f"(--x/--y) or fix it with --select {free[0]}=VALUE")
    gi = grid_index(m, np)
    keep = np.ones(m["n"], dtype=bool)
    at = []
    for a, vals in zip(axes, g["values"]):
        if a in (x, y):
            continue
        j = 0
        if a in fixed:
            j = nearest_index(vals, fixed[a], np)
            keep &= gi[a] == j
            notes.append(f"--select {a}={fmt(fixed[a])} -> {a}={fmt(vals[j])} "
                         f"(value {j + 1} of {len(vals)})")
        at.append(f"{a}={fmt(vals[j])}")
    xi = axes.index(x)
    yi = axes.index(y) if y else None
    xv = g["values"][xi]
    yv = g["values"][yi] if y else np.array([0.0])
    rows_idx = np.full((len(yv), len(xv)), -1)
    for i in np.flatnonzero(keep):
        rows_idx[gi[y][i] if y else 0, gi[x][i]] = i
    if np.any(rows_idx < 0):  # cannot happen with one value per other axis
        raise UserError("the selection does not give one case per cell")
    idx = rows_idx
    done = (m["status"] == 1)[idx]

    scales = {"a": m["mu_scale"], "b": m["mu_scale"], "a_minus_b": m["mu_scale"], "d_c": m["a"]}
    a_name = m["a_name"]
    units = {"a": f"{a_name}/R", "b": f"{a_name}/R", "a_minus_b": f"{a_name}/R", "d_c": a_name}

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import colors

    xkind = axis_kind(xv, g["log"][xi], np)
    ykind = axis_kind(yv, g["log"][yi], np) if y else "linear"
    xc, yc = coords(xv, xkind, np), coords(yv, ykind, np)
    suffix = {"log": " (log10)", "category": " (categories)", "linear": ""}
    fig, axs = plt.subplots(2, 2, figsize=(11.5, 8.6))
    table = []
    for ax, (name, label) in zip(axs.ravel(), METRICS):
        z = data[name][idx].astype(float)
        if not args.unscaled:
            with np.errstate(divide="ignore", invalid="ignore"):
                z = z / scales[name][idx]
        z[~done] = np.nan
        n_nd = int(np.sum(~done))
        n_undef = int(np.sum(done & ~np.isfinite(z)))
        ok = np.isfinite(z)
        unit = "" if args.unscaled else f" / {units[name]}"
        if name == "d_c":
            finite = z[ok]
            cmap = plt.get_cmap("viridis").copy()
            if finite.size and np.all(finite > 0) and finite.max() / finite.min() > 30:
                norm = colors.LogNorm(vmin=finite.min(), vmax=finite.max())
            else:
                norm = colors.Normalize(vmin=finite.min() if finite.size else 0,
                                        vmax=finite.max() if finite.size else 1)
        else:
            cmap = plt.get_cmap("RdBu_r").copy()
            top = float(np.max(np.abs(z[ok]))) if ok.any() else 1.0
            top = top or 1e-16
            norm = colors.Normalize(vmin=-top, vmax=top)
        cmap.set_bad("white")
        if y:
            mesh = ax.pcolormesh(edges(xc, np), edges(yc, np), np.ma.masked_invalid(z), cmap=cmap,
                                 norm=norm, shading="flat", edgecolors="0.85", linewidth=0.3)
            cb = fig.colorbar(mesh, ax=ax)
            cb.set_label(f"{label}{unit}", fontsize=9)
            ax.set_ylabel(y + suffix[ykind])
            if ykind == "category":
                ax.set_yticks(yc, [fmt(t) for t in yv])
        else:
            ax.plot(xc, z[0], "o-", ms=4)
            ax.set_ylabel(f"{label}{unit}")
            ax.grid(True, alpha=0.3)
        ax.set_xlabel(x + suffix[xkind])
        if xkind == "category":
            ax.set_xticks(xc, [fmt(t) for t in xv])
        ax.set_title(f"{label}{unit}: {int(ok.sum())} defined, {n_undef} undefined"
                     + (f", {n_nd} not done" if n_nd else ""), fontsize=9)
        fz = z[ok]
        table.append((name, int(ok.sum()), n_undef, n_nd,
                      float(fz.min()) if fz.size else math.nan,
                      float(np.median(fz)) if fz.size else math.nan,
                      float(fz.max()) if fz.size else math.nan, unit.strip(" /") or "as stored"))
    k = args.event
    head = args.title or (f"{os.path.basename(args.map)}: rate-and-state parameters of event {k} "
                          f"(segment {k} \u2192 {k + 1})" + (f"\nat {', '.join(at)}"
                                                             if at else ""))
    fig.suptitle(head + "\nblank: undefined (hold, equal velocities, no 1/e decay) or not done",
                 fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    for note in notes:
        print(f"{PROG}: {note}")
    print(f"event {k} over {x} ({len(xv)} values, {xkind})"
          + (f" x {y} ({len(yv)} values, {ykind})" if y else "")
          + (f"; at {', '.join(at)}" if at else ""))
    print(f"{'metric':<10} {'unit':>9} {'defined':>8} {'undefined':>10} {'not done':>9} "
          f"{'min':>11} {'median':>11} {'max':>11}")
    for name, nd, nu, nn, lo, med, hi, unit in table:
        print(f"{name:<10} {unit:>9} {nd:>8} {nu:>10} {nn:>9} {lo:>11.4g} {med:>11.4g} {hi:>11.4g}")
    save_figure(fig, output, args.dpi)
    print(f"{PROG}: wrote {output}")
    return 0


if __name__ == "__main__":
    sys.exit(run_tool(main, PROG))
