# pyrun-needs: numpy matplotlib h5py
"""The friction-velocity curve of an mdrmap-map/2 map: stationary friction against
the sliding velocity in similarity variables.

Under load it plots the stationary friction before t = 0, results/mu_pre
(markers) and analytic/mu_pre (line, the closed form of docs/design.md, "Load
control"), over the map's scales: mu / (a0/R) (/scales/friction) against
zeta0 = v tau / a0 (v times /scales/time over /scales/length; a0 the Hertz
radius of the load), one curve per value of the other case parameters; the
closed form has one maximum, at zeta0* = 1.39796 with mu* = 0.88627 a0/R
(marked +). At fixed depth it plots mu / (a1/R) against zeta = v tau / a1
(a1 the leading edge at the depth) instead, with the closed form M(b) as a
thin black line; that curve rises monotonically to 4/3 (no maximum).

The stationary state before t = 0 does not depend on the history, so cases
that differ only in their history give one point (the first done one).

Per curve it prints the largest measured value and, when it lies inside the v
range, the maximum interpolated by a parabola in ln(zeta0) through the three
points around it, for the map's values (results) and for the closed form at the
same velocities (analytic), with their deviations from zeta0* and mu*. Cases
with tau = 0 (no viscosity: mu = 0) and cases not done are skipped and counted.

Usage:
    python3 -m mdrmap map_friction_velocity load_sweep.h5 -o friction_velocity.png
    python3 -m mdrmap map_friction_velocity load_sweep.h5 --select R=1 -o fv.png

Exit codes: 0 success, 2 bad input (one line on stderr).
"""

import math
import os
import sys

from ._maplib import (MU_STAR, SELECT_HELP, ZETA0_STAR, UserError, add_figure_options,
                    add_select_option, fmt, map_tool_parser, open_map2, parse_map_tool_args,
                    read_masked, run_tool, save_figure, select_cases)

PROG = "map_friction_velocity"


def closed_form_depth(np, n=4000):
    """At fixed depth: (zeta = v tau / a1, mu / (a1/R)) = ((1-b^2)/(2b), M(b))."""
    b = np.logspace(-7, 0, n)[:-1]
    M = (1 - b) * (b * b - b + 4) / (b * b - 2 * b + 3)
    return ((1 - b * b) / (2 * b))[::-1], M[::-1]


def peak(x, y, np):
    """(x_max, y_max, interior): the largest y, refined by a parabola in ln x through
    its neighbours when it is not at an end of the (sorted) x."""
    ok = np.isfinite(y) & (x > 0)
    x, y = x[ok], y[ok]
    if x.size == 0:
        return math.nan, math.nan, False
    j = int(np.argmax(y))
    if j == 0 or j == x.size - 1:
        return float(x[j]), float(y[j]), False
    lx = np.log(x[j - 1:j + 2])
    c = np.polyfit(lx, y[j - 1:j + 2], 2)
    if not c[0] < 0:
        return float(x[j]), float(y[j]), False
    xm = -c[1] / (2 * c[0])
    return float(math.exp(xm)), float(np.polyval(c, xm)), True


def read(args, sel, np):
    """(m, mu, mu_an, use, notes): the map's cases, results/mu_pre and
    analytic/mu_pre, the cases to plot (selected, done, tau > 0, v > 0)."""
    f, m = open_map2(args.map, np, PROG)
    with f:
        for need in ("results/mu_pre", "analytic/mu_pre"):
            if need not in f:
                raise UserError(f"{args.map} is an incomplete mdrmap map (no /{need})")
        mu = read_masked(f["results/mu_pre"])
        mu_an = read_masked(f["analytic/mu_pre"])
    keep, notes = select_cases(m, sel, np, "--select")
    c, done = m["cols"], m["status"] == 1
    n_notdone = int(np.sum(keep & ~done))
    relaxes = m["scales"]["time"] > 0  # tau > 0 or a spectrum: not purely elastic
    elastic = keep & done & ~relaxes
    if n_notdone:
        notes.append(f"skipped {n_notdone} case(s) not done (failed or pending)")
    if elastic.any():
        notes.append(f"skipped {int(elastic.sum())} purely elastic case(s) (mu = 0)")
    return m, mu, mu_an, keep & done & relaxes & (c["v"] > 0), notes


def group_curves(m, use, path, np):
    """(curves {key: {v: case}}, gcols, varying): one curve per value of the
    other case parameters (as the map's /schema lists them), one point per v."""
    c = m["cols"]
    gcols = [k for k in c if k != "v"]
    curves = {}
    for i in np.flatnonzero(use):
        curves.setdefault(tuple(float(c[k][i]) for k in gcols), {}).setdefault(
            float(c["v"][i]), int(i))
    if not curves:
        raise UserError(f"{path}: no done case with tau > 0 to plot")
    if max(len(v) for v in curves.values()) < 2:
        raise UserError(f"{path} has one velocity v per ({', '.join(gcols)}): no "
                        f"friction-velocity curve (the map needs a v axis)")
    varying = [k for j, k in enumerate(gcols) if len({key[j] for key in curves}) > 1]
    return curves, gcols, varying


def plot_curves(ax, plt, m, mu, mu_an, grouped, np):
    """Draws each curve (scaled by the map's scales); the rows report() prints."""
    curves, gcols, varying = grouped
    colours = plt.get_cmap("viridis" if len(curves) > 10 else "tab10")
    rows = []
    for ci, (key, byv) in enumerate(sorted(curves.items())):
        idx = np.array([byv[v] for v in sorted(byv)])
        x, y, ya = m["zeta"][idx], mu[idx] / m["mu_scale"][idx], mu_an[idx] / m["mu_scale"][idx]
        order = np.argsort(x)
        x, y, ya = x[order], y[order], ya[order]
        col = colours(ci / max(len(curves) - 1, 1)) if len(curves) > 10 else colours(ci % 10)
        label = ", ".join(f"{k}={fmt(key[gcols.index(k)])}" for k in (varying or gcols[:1]))
        ax.plot(x, ya, "-", color=col, lw=1.2, alpha=0.8)
        ax.plot(x, y, "o", color=col, ms=4.5, mfc="none", label=label)
        xm, ym, inside = peak(x, y, np)
        xa, yam, inside_a = peak(x, ya, np)
        if inside:
            ax.plot([xm], [ym], "x", color=col, ms=9, mew=1.6)
        rows.append((label, len(x), float(x.min()), float(x.max()), xm, ym, inside, xa, yam, inside_a,
                     float(np.nanmax(np.abs(y - ya) / np.abs(ya))) if np.any(ya != 0) else 0.0))
    return rows


def figure(m, mu, mu_an, grouped, args, np):
    """The figure and the rows of its curves."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    load, a_name, xname = m["loading"] == "force", m["a_name"], m["zeta_name"]
    fig, ax = plt.subplots(figsize=(8, 5.4))
    rows = plot_curves(ax, plt, m, mu, mu_an, grouped, np)
    if load:
        ax.plot([ZETA0_STAR], [MU_STAR], "+", color="black", ms=14, mew=1.6,
                label=f"maximum: {xname}* = {ZETA0_STAR:.5f}, \u03bc* = {MU_STAR:.5f} a0/R")
    else:
        zc, mc = closed_form_depth(np)
        ax.plot(zc, mc, "-", color="black", lw=0.8, zorder=1, label="closed form M(b)")
    xs = np.concatenate([[r[2], r[3]] for r in rows])
    ax.set_xscale("log")
    ax.set_xlim(xs.min() / 1.5, xs.max() * 1.5)
    ax.set_xlabel(f"\u03b6{'0' if load else ''} = v \u03c4 / {a_name}  (/scales: length "
                  f"{a_name}, time \u03c4)")
    ax.set_ylabel(f"stationary \u03bc / ({a_name}/R)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    title = args.title or (f"{os.path.basename(args.map)}: friction-velocity curve "
                           + ("under load" if load else "at fixed depth")
                           + "\no: results/mu_pre, line: analytic/mu_pre, \u00d7: interpolated maximum")
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    return fig, rows


def report(m, rows):
    """Prints each curve's range and maximum (and, under load, against theory)."""
    load, a_name, xname = m["loading"] == "force", m["a_name"], m["zeta_name"]
    w = max(len(r[0]) for r in rows + [("curve",)])
    print(f"{'curve':<{w}}  points  {xname + ' range':>17}  {'max ' + xname:>10}  "
          f"{'mu/(' + a_name + '/R)':>11}  {'analytic ' + xname:>14}  {'analytic mu':>11}  "
          f"{'max |res-an|':>12}")
    for (label, npt, lo, hi, xm, ym, inside, xa, yam, inside_a, dev) in rows:
        mark = "" if inside else "*"
        mark_a = "" if inside_a else "*"
        print(f"{label:<{w}}  {npt:>6}  {fmt(lo, 3):>8}..{fmt(hi, 3):<8}  "
              f"{xm:>9.5g}{mark:1}  {ym:>11.5g}  {xa:>13.5g}{mark_a:1}  {yam:>11.5g}  {dev:>12.2e}")
    if any(not r[6] or not r[9] for r in rows):
        print(f"  *: the largest value is at an end of the {xname} range (not bracketed): "
              f"the map's velocities do not reach the maximum")
    if not load:
        print("at fixed depth the stationary mu rises monotonically with zeta to 4/3 a1/R: "
              "no maximum")
        return
    print(f"theory: {xname}* = {ZETA0_STAR:.6f}, mu*/(a0/R) = {MU_STAR:.6f} "
          f"(docs/design.md, \"Load control\")")
    for (label, npt, lo, hi, xm, ym, inside, xa, yam, inside_a, dev) in rows:
        if inside:
            print(f"maximum of {label}: {xname} = {xm:.5g} ({100 * (xm / ZETA0_STAR - 1):+.2f}% "
                  f"from {xname}*), mu = {ym:.5g} ({100 * (ym / MU_STAR - 1):+.2f}% from mu*); "
                  f"analytic: {xname} = {xa:.5g} ({100 * (xa / ZETA0_STAR - 1):+.2f}%), "
                  f"mu = {yam:.5g} ({100 * (yam / MU_STAR - 1):+.2f}%)")
        else:
            print(f"maximum of {label}: not bracketed by {xname} = {fmt(lo)} .. {fmt(hi)}")


def main(argv=None):
    ap = map_tool_parser(PROG, __doc__, "mdrmap-map/2 map (.h5) with several velocities v",
                         "_friction_velocity.png")
    add_select_option(ap, SELECT_HELP + ", e.g. --select tau=1")
    add_figure_options(ap)
    args, sel, output = parse_map_tool_args(ap, argv)

    import numpy as np

    m, mu, mu_an, use, notes = read(args, sel, np)
    grouped = group_curves(m, use, args.map, np)
    fig, rows = figure(m, mu, mu_an, grouped, args, np)
    for note in notes:
        print(f"{PROG}: {note}")
    report(m, rows)
    save_figure(fig, output, args.dpi)
    print(f"{PROG}: wrote {output}")
    return 0


if __name__ == "__main__":
    sys.exit(run_tool(main, PROG))
