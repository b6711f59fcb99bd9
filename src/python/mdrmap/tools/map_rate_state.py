# pyrun-needs: numpy matplotlib h5py
"""Maps of the apparent rate-and-state parameters of one event of an
mdrmap-map/2 grid study over two of its grid axes.

Four panels for event K (default 0: the change at t = 0 from v to w1; event k
is the change at the start of segment k + 1): the direct effect a, the
evolution b, a - b (events/a, b, a_minus_b; docs/design.md "Event metrics":
with a parallel dashpot a is the jump at the change, without one (tau = 0, a
spectrum) it is read from the peak after the change, and D_c from there),
each in the map's scale for its /schema unit (/scales/friction: a0/R under
load, a1/R at fixed depth, for a, b, a - b; /scales/length: a0 or a1, for
D_c). `--unscaled` plots the map's values as they are. Colours of a, b and
a - b are symmetric about 0 (blue < 0 < red).

`--x AXIS --y AXIS` name the two grid axes (default: the two with the most
values, the longer on x); an axis is drawn logarithmically when /grid marks it
so (attribute `log`) or its values are geometric. Every other grid axis with
more than one value must be fixed with `--select AXIS=VALUE` (the grid value
nearest to VALUE is taken, and the tool says which) unless it has one value.
Undefined values (the fill value: a hold, equal velocities, no transient,
a peak that is the segment's end, a deviation that does not decay to 1/e
within the segment) are drawn blank (white) and counted,
and so are cases not done.

Prints a table per panel: how many cells are defined, undefined and not done,
and the minimum, median and maximum of the defined ones.

Usage:
    python3 -m mdrmap map_rate_state load_sweep.h5 --x v --y F0 -o rate_state.png
    python3 -m mdrmap map_rate_state velocity_steps.h5 --event 1 --x v -o rs.png
    python3 -m mdrmap map_rate_state seed_step.h5 --x v --y w1_over_v --select tau=2 -o rs.png

Exit codes: 0 success, 2 bad input (one line on stderr).
"""

import math
import os
import sys

from ._maplib import (UserError, add_figure_options, add_select_option, fmt,
                    grid_index, map_tool_parser, nearest_index, open_map2, parse_map_tool_args,
                    read_masked, resolve_axis, run_tool, save_figure, scale_of, scale_symbol)

PROG = "map_rate_state"
METRICS = [("a", "direct effect a"), ("b", "evolution b"), ("a_minus_b", "a \u2212 b"),
           ("D_c", "D$_c$")]


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


def read_metrics(args, np):
    """(m, {metric: values of event K [N]}) of the map."""
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
    if m["grid"] is None:
        raise UserError(f"{args.map} is a [cases] map (no /grid): this tool maps a grid study "
                        f"over two grid axes")
    return m, data


def pick_axes(args, sel, axes, shape):
    """(x, y, fixed {axis: value}): the plotted axes and the --select ones."""
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
    if free:
        raise UserError(f"grid axis {free[0]} has {shape[axes.index(free[0])]} values: plot it "
                        f"(--x/--y) or fix it with --select {free[0]}=VALUE")
    return x, y, fixed


def plan_cells(args, sel, m, np):
    """{"x", "y", "xv", "yv", "xkind", "ykind", "idx" (the case of each cell,
    [len(yv), len(xv)]), "at" (the fixed axes' values), "notes"}."""
    g = m["grid"]
    axes = g["axes"]
    x, y, fixed = pick_axes(args, sel, axes, g["shape"])
    gi = grid_index(m, np)
    keep = np.ones(m["n"], dtype=bool)
    at, notes = [], []
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
    xi, yi = axes.index(x), (axes.index(y) if y else None)
    xv = g["values"][xi]
    yv = g["values"][yi] if y else np.array([0.0])
    idx = np.full((len(yv), len(xv)), -1)
    for i in np.flatnonzero(keep):
        idx[gi[y][i] if y else 0, gi[x][i]] = i
    if np.any(idx < 0):  # cannot happen with one value per other axis
        raise UserError("the selection does not give one case per cell")
    return {"x": x, "y": y, "xv": xv, "yv": yv, "idx": idx, "at": at, "notes": notes,
            "xkind": axis_kind(xv, g["log"][xi], np),
            "ykind": axis_kind(yv, g["log"][yi], np) if y else "linear"}


def panel_norm(name, z, ok, plt, colors, np):
    """(colour map, norm): D_c sequential (log over a wide range), the others symmetric."""
    if name == "D_c":
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
        norm = colors.Normalize(vmin=-(top or 1e-16), vmax=top or 1e-16)
    cmap.set_bad("white")
    return cmap, norm


def panel(ax, fig, plt, colors, p, name, label, z, unit, np):
    """Draws one metric z [len(yv), len(xv)]."""
    ok = np.isfinite(z)
    cmap, norm = panel_norm(name, z, ok, plt, colors, np)
    xc, yc = coords(p["xv"], p["xkind"], np), coords(p["yv"], p["ykind"], np)
    suffix = {"log": " (log10)", "category": " (categories)", "linear": ""}
    if p["y"]:
        mesh = ax.pcolormesh(edges(xc, np), edges(yc, np), np.ma.masked_invalid(z), cmap=cmap,
                             norm=norm, shading="flat", edgecolors="0.85", linewidth=0.3)
        fig.colorbar(mesh, ax=ax).set_label(f"{label}{unit}", fontsize=9)
        ax.set_ylabel(p["y"] + suffix[p["ykind"]])
        if p["ykind"] == "category":
            ax.set_yticks(yc, [fmt(t) for t in p["yv"]])
    else:
        ax.plot(xc, z[0], "o-", ms=4)
        ax.set_ylabel(f"{label}{unit}")
        ax.grid(True, alpha=0.3)
    ax.set_xlabel(p["x"] + suffix[p["xkind"]])
    if p["xkind"] == "category":
        ax.set_xticks(xc, [fmt(t) for t in p["xv"]])


def figure(m, data, p, args, np):
    """The four panels, each metric in the map's scale for its /schema unit
    (scale_of: a, b, a - b by /scales/friction, D_c by /scales/length); the table."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import colors

    idx = p["idx"]
    done = (m["status"] == 1)[idx]
    fig, axs = plt.subplots(2, 2, figsize=(11.5, 8.6))
    table = []
    for ax, (name, label) in zip(axs.ravel(), METRICS):
        z = data[name][idx].astype(float)
        scale = None if args.unscaled else scale_of(m, f"events/{name}")
        if scale:
            with np.errstate(divide="ignore", invalid="ignore"):
                z = z / m["scales"][scale][idx]
        z[~done] = np.nan
        n_nd, ok = int(np.sum(~done)), np.isfinite(z)
        n_undef = int(np.sum(done & ~ok))
        unit = f" / {scale_symbol(m, scale)}" if scale else ""
        panel(ax, fig, plt, colors, p, name, label, z, unit, np)
        ax.set_title(f"{label}{unit}: {int(ok.sum())} defined, {n_undef} undefined"
                     + (f", {n_nd} not done" if n_nd else ""), fontsize=9)
        fz = z[ok]
        stats = [float(q(fz)) if fz.size else math.nan for q in (np.min, np.median, np.max)]
        table.append((name, int(ok.sum()), n_undef, n_nd, *stats, unit.strip(" /") or "as stored"))
    k, at = args.event, p["at"]
    head = args.title or (f"{os.path.basename(args.map)}: rate-and-state parameters of event {k} "
                          f"(segment {k} \u2192 {k + 1})" + (f"\nat {', '.join(at)}" if at else ""))
    fig.suptitle(head + "\nblank: undefined (hold, equal velocities, no 1/e decay) or not done",
                 fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    return fig, table


def report(p, table, k):
    at = p["at"]
    print(f"event {k} over {p['x']} ({len(p['xv'])} values, {p['xkind']})"
          + (f" x {p['y']} ({len(p['yv'])} values, {p['ykind']})" if p["y"] else "")
          + (f"; at {', '.join(at)}" if at else ""))
    print(f"{'metric':<10} {'unit':>9} {'defined':>8} {'undefined':>10} {'not done':>9} "
          f"{'min':>11} {'median':>11} {'max':>11}")
    for name, nd, nu, nn, lo, med, hi, unit in table:
        print(f"{name:<10} {unit:>9} {nd:>8} {nu:>10} {nn:>9} {lo:>11.4g} {med:>11.4g} {hi:>11.4g}")


def main(argv=None):
    ap = map_tool_parser(PROG, __doc__, "mdrmap-map/2 map (.h5) of a grid study",
                         "_rate_state.png")
    ap.add_argument("--event", type=int, default=0, metavar="K",
                    help="0-based event: the change at the start of segment K+1 (default 0)")
    ap.add_argument("--x", default=None, metavar="AXIS", help="grid axis on x")
    ap.add_argument("--y", default=None, metavar="AXIS", help="grid axis on y")
    add_select_option(ap, "fix another grid axis at its value nearest to VALUE (repeatable)")
    ap.add_argument("--unscaled", action="store_true",
                    help="plot a, b, a-b and D_c as stored (no division by the map's /scales)")
    add_figure_options(ap)
    args, sel, output = parse_map_tool_args(ap, argv)

    import numpy as np

    m, data = read_metrics(args, np)
    p = plan_cells(args, sel, m, np)
    fig, table = figure(m, data, p, args, np)
    for note in p["notes"]:
        print(f"{PROG}: {note}")
    report(p, table, args.event)
    save_figure(fig, output, args.dpi)
    print(f"{PROG}: wrote {output}")
    return 0


if __name__ == "__main__":
    sys.exit(run_tool(main, PROG))
