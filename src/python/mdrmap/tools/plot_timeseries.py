# pyrun-needs: numpy matplotlib h5py
"""Plot the response to velocity changes from an mdrmap map (the seed paper's Figure 2).

One panel per time series of a map written with `timeseries = true` (or
`--timeseries true`), as its /schema lists them (F_N, F_x, mu, a2, and d, a1
under load), against time over all segments ([N, K*S]; t from the first
change at t = 0), for one or more cases. Labels and units come from the
map's /schema.

Time is t / tau (the map's /scales/time; t when a plotted case has tau = 0).
Besides the simulated curve of each case (from /timeseries) the panels show:

  - the stationary level before t = 0 (results/*_pre), as a short segment at
    t < 0, joined to the value at t = 0+ by a thin dotted jump;
  - at fixed depth, the corrected estimate just after the first change
    (analytic/*_jump, eqs. 15/16), as an open circle at t = 0;
  - the stationary level of the last segment (analytic/<q>_ss), dashed;
  - for a2 of a one-segment map, when a case has w1/v <= 1e-3, the start-stop
    limit a2 = a1 (1 - exp(-t/tau))^(1/2) (for v tau >> a1 and w1 tau << a1).

Lengths are divided by the map's length scale (/scales/length: a1 at depth,
a0 under load); `--scaled` divides every quantity by the map's scale for its
/schema unit (/scales: forces by the force scale, depths by the depth scale,
mu by the friction scale a/R); cases with the same zeta = v tau / a and
zeta1 = w1 tau / a then fall on the same curves.

`--zoom` scales the force axes to t >= 0 only (the forces can drop by orders of
magnitude at the step); the level before the step is then written as an
arrow with its value when it is off the axis.

Cases: `--case I` (repeatable, 0-based row of the map, or `all` for every done
case), `--select d=1e-3,w1_over_v=1e-4` (repeatable; the done case nearest in
those parameters: the /cases columns (d or F0, R, tau, G, v), w1, T1, ...,
w1_over_v, T1_over_tau, ... (v1, v1_over_v: the seed's names of w1,
w1_over_v) and zeta, zeta1; log distance for positive values), default the
first done case. Cases that are pending or failed are skipped, and the tool
says how many.

Usage:
    python3 -m mdrmap plot_timeseries MAP.h5 -o figure2.png
    python3 -m mdrmap plot_timeseries MAP.h5 --case all --scaled -o figure2.png
    python3 -m mdrmap plot_timeseries MAP.h5 --select d=1e-3,v=10 -o case.png

Exit codes: 0 success, 2 bad input (one line on stderr).
"""

import argparse
import math
import os
import sys

from ._maplib import (Parser, UserError, load_cases, open_map, read_masked, run_tool, save_figure,
                    scale_of, scale_symbol)

PROG = "plot_timeseries"
MAX_LISTED = 8  # skipped cases listed by number at most


def fmt(x):
    """Compact number: 1e-04 -> 1e-4, 10000 -> 1e4, 0.5 -> 0.5."""
    if x == 0:
        return "0"
    s = f"{x:.3g}"
    if "e" in s:
        mant, exp = s.split("e")
        return f"{mant}e{int(exp)}"
    return s


def load(path, np, h5py):
    """The map in the form the plot reads: its cases (load_cases) with every
    /cases column, wk, Tk, wk_over_v, Tk_over_tau, zeta, zeta1 as m[name];
    "quant": the time series /schema lists (not t, segment), "ts" their
    values, and results/<q>_pre, analytic/<q>_jump, analytic/<q>_post (the
    last segment's stationary level) where the map has them."""
    with open_map(path, h5py, PROG) as f:
        c = load_cases(f, path, np)
        m = dict(c)
        quant = [k.split("/", 1)[1] for k, (unit, _) in c["schema"].items()
                 if k.startswith("timeseries/") and unit not in ("time", "count")]
        if not quant or any(f"timeseries/{s}" not in f for s in ["t"] + quant):
            raise UserError(f"{path} has no /timeseries; rerun the study with "
                            f"`--timeseries true` (or timeseries = true in [run])")
        m["quant"] = quant
        case_columns(m, c, np)
        n, K = c["n"], c["K"]
        for q in quant:
            for grp, name in [("results", f"{q}_pre"), ("analytic", f"{q}_jump")]:
                if f"{grp}/{name}" in f and f[f"{grp}/{name}"].shape == (n,):
                    m[f"{grp}/{name}"] = read_masked(f[f"{grp}/{name}"])
            if f"analytic/{q}_ss" in f:  # the stationary level of the last segment
                m[f"analytic/{q}_post"] = read_masked(f[f"analytic/{q}_ss"]).reshape(n, K)[:, -1]
        m["ts"] = {s: np.asarray(f[f"timeseries/{s}"][()], dtype=float) for s in ["t"] + quant}
    return m


def case_columns(m, c, np):
    """m[name] for the /cases columns, the history's wk, Tk, wk_over_v,
    Tk_over_tau (v1, v1_over_v: the seed's names of w1, w1_over_v) and zeta,
    zeta1 (the map's scales); m["case_cols"], m["derived"]."""
    K = c["K"]
    m.update(c["cols"])
    for j in range(K):
        m[f"w{j + 1}"], m[f"T{j + 1}"] = c["w"][:, j], c["T"][:, j]
        with np.errstate(divide="ignore", invalid="ignore"):
            m[f"w{j + 1}_over_v"] = c["w"][:, j] / c["cols"]["v"]
            m[f"T{j + 1}_over_tau"] = c["T"][:, j] / c["scales"]["time"]
    m["case_cols"] = list(c["cols"]) + [f"{kind}{j + 1}" for j in range(K) for kind in "wT"]
    m["v1"], m["v1_over_v"] = m["w1"], m["w1_over_v"]
    with np.errstate(divide="ignore", invalid="ignore"):
        m["zeta1"] = m["v1"] * c["scales"]["time"] / c["a"]
    m["derived"] = ["zeta", "zeta1"] + [f"{kind}{j + 1}_over_{ref}" for j in range(K)
                                        for kind, ref in (("w", "v"), ("T", "tau"))] + \
        ["v1", "v1_over_v"]


def parse_select(spec, names):
    out = {}
    for part in spec.split(","):
        part = part.strip()
        if not part:
            continue
        if "=" not in part:
            raise UserError(f"--select {spec}: expected NAME=VALUE[,NAME=VALUE...]")
        k, v = (s.strip() for s in part.split("=", 1))
        if k not in names:
            raise UserError(f"--select {spec}: unknown parameter {k!r} "
                            f"(valid: {', '.join(names)})")
        try:
            out[k] = float(v)
        except ValueError:
            raise UserError(f"--select {spec}: {k}={v!r} is not a number") from None
        if not math.isfinite(out[k]):
            raise UserError(f"--select {spec}: {k}={v!r} is not a finite number")
    if not out:
        raise UserError(f"--select {spec!r}: expected NAME=VALUE[,NAME=VALUE...]")
    return out


def nearest_case(m, spec, np):
    done = np.flatnonzero(m["status"] == 1)
    if done.size == 0:
        return None
    dist = np.zeros(done.size)
    for k, target in spec.items():
        col = m[k][done]
        if target > 0 and np.all(col > 0):
            dist += np.abs(np.log10(col / target))
        else:
            span = np.ptp(m[k]) or max(abs(target), 1.0)
            dist += np.abs(col - target) / span
    return int(done[int(np.argmin(dist))])


def case_params(m, i, uni=True):
    tau, zeta, zeta1 = ("\u03c4", "\u03b6", "\u03b6\u2081") if uni else ("tau", "zeta", "zeta1")
    s = ", ".join(f"{tau if c == 'tau' else c}={fmt(m[c][i])}" for c in m["case_cols"]
                  if c != "G" or m["G"][i] != 1)
    if m["scales"]["time"][i] > 0:
        s += f"  ({zeta}={fmt(m['zeta'][i])}, {zeta1}={fmt(m['zeta1'][i])})"
    return s


def choose_cases(args, m, np):
    """Returns (cases to plot, notes to print)."""
    n = m["n"]
    notes = []
    wanted = []
    for c in args.case or []:
        if c.strip().lower() == "all":
            wanted.extend(range(n))
            continue
        try:
            i = int(c)
        except ValueError:
            raise UserError(f"--case {c!r}: expected a case number (0..{n - 1}) or 'all'") from None
        if i < 0:
            i += n
        if not 0 <= i < n:
            raise UserError(f"--case {c}: the map has {n} cases (0..{n - 1})")
        wanted.append(i)
    for spec in args.select or []:
        sel = parse_select(spec, m["case_cols"] + m["derived"])
        i = nearest_case(m, sel, np)
        if i is None:
            break  # reported below: no done case
        notes.append(f"--select {spec} -> case {i}: {case_params(m, i, uni=False)}")
        wanted.append(i)
    if not args.case and not args.select:
        done = np.flatnonzero(m["status"] == 1)
        if done.size:
            wanted.append(int(done[0]))
    return done_cases(args, m, wanted, notes, np)


def done_cases(args, m, wanted, notes, np):
    """(the done ones of the wanted cases, notes): the others noted as skipped;
    UserError when none is done."""
    n = m["n"]
    seen, cases, skipped = set(), [], []
    for i in wanted:
        if i in seen:
            continue
        seen.add(i)
        (cases if m["status"][i] == 1 else skipped).append(i)
    n_failed = int(np.sum(m["status"] == -1))
    n_pending = int(np.sum(m["status"] == 0))
    if skipped:
        kinds = {-1: "failed", 0: "pending"}
        listed = ", ".join(f"{i} ({kinds.get(int(m['status'][i]), 'status ' + str(m['status'][i]))})"
                           for i in skipped[:MAX_LISTED])
        more = f" and {len(skipped) - MAX_LISTED} more" if len(skipped) > MAX_LISTED else ""
        notes.append(f"skipped {len(skipped)} case{'s' if len(skipped) != 1 else ''} "
                     f"not done: {listed}{more}")
    elif not (args.case or args.select) and (n_failed or n_pending):
        notes.append(f"the map holds {n_failed} failed and {n_pending} pending cases "
                     f"(skipped)")
    if not cases:
        if not np.any(m["status"] == 1):
            raise UserError(f"{m['path']} has no done case ({n_failed} failed, "
                            f"{n_pending} pending of {n})")
        raise UserError("none of the chosen cases is done (skipped "
                        f"{len(skipped)}: failed or pending)")
    return cases, notes


def build_parser():
    ap = Parser(prog=PROG, description=__doc__,
                formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("map", help="mdrmap map (.h5) written with timeseries = true")
    ap.add_argument("-o", "--output", default=None,
                    help="PNG to write (default: <map name>_timeseries.png in the current directory)")
    ap.add_argument("--case", action="append", metavar="I",
                    help="case number (0-based row of the map), repeatable; 'all' for every done case")
    ap.add_argument("--select", action="append", metavar="SPEC",
                    help="the done case nearest to SPEC, e.g. d=1e-3,w1_over_v=1e-4 "
                         "(names: the /cases columns, wk, Tk, wk_over_v, Tk_over_tau, zeta, "
                         "zeta1); repeatable")
    ap.add_argument("--scaled", action="store_true",
                    help="divide by the map's /scales (force, depth, friction a/R)")
    ap.add_argument("--ylog", choices=["auto", "on", "off"], default="auto",
                    help="log y axis for F_N, F_x, mu: auto = when the values span more "
                         "than two decades (default auto)")
    ap.add_argument("--start-stop", choices=["auto", "on", "off"], default="auto",
                    help="draw a1 (1-exp(-t/tau))^(1/2) in the a2 panel: auto = when a case "
                         "has w1/v <= 1e-3 (default auto)")
    ap.add_argument("--zoom", action="store_true",
                    help="scale the force axes to t >= 0; a level before the step above "
                         "the range is written as an arrow with its value")
    ap.add_argument("--t-max", type=float, default=None, metavar="T",
                    help="right end of the time axis (in t/tau, or t when tau = 0)")
    ap.add_argument("--title", default=None, help="figure title")
    ap.add_argument("--dpi", type=int, default=120, help="resolution (default 120)")
    return ap


def scale(m, q, i, args):
    """What quantity q of case i is divided by: its /scales entry (lengths
    always, the others with --scaled), else 1."""
    sc = scale_of(m, f"timeseries/{q}")
    if sc is None or (sc != "length" and not args.scaled):
        return 1.0
    return m["scales"][sc][i]


def labels(m, q, args):
    """(panel title, y label) of quantity q from its /schema unit and meaning."""
    unit, meaning = m["schema"][f"timeseries/{q}"]
    sc = scale_of(m, f"timeseries/{q}")
    what = meaning.split(" at the output instants")[0]
    if sc is not None and (sc == "length" or args.scaled):
        return what, f"{q} / {scale_symbol(m, sc)}"
    return what, f"{q}  [{unit}]" if unit and unit != "number" else q


def draw_case(ax, m, q, i, c, xs, xmax, pre_len, args, values, pre_levels, zoom):
    """Case i's curve, level before t = 0, estimate at 0+ and final level."""
    s = scale(m, q, i, args)
    y, x = m["ts"][q][i] / s, xs[i]
    keep = x <= xmax * (1 + 1e-12)
    ax.plot(x[keep], y[keep], color=c, lw=1.6, zorder=3)
    values.append(y[keep])
    pre = m.get(f"results/{q}_pre")
    if pre is not None:
        yp = pre[i] / s
        ax.plot([-pre_len, 0], [yp, yp], color=c, lw=1.6, zorder=3)
        ax.plot([0, 0], [yp, y[0]], color=c, lw=0.8, ls=":", zorder=2)
        (pre_levels if zoom else values).append((c, yp) if zoom else np_array(yp))
    jump = m.get(f"analytic/{q}_jump")
    if jump is not None:
        ax.plot([0], [jump[i] / s], marker="o", ms=8, mfc="none", mec=c, mew=1.4, ls="none",
                zorder=4)
        values.append(np_array(jump[i] / s))
    post = m.get(f"analytic/{q}_post")
    if post is not None:
        ax.plot([0, xmax], [post[i] / s] * 2, color=c, lw=1.0, ls="--", alpha=0.75, zorder=2)
        values.append(np_array(post[i] / s))


def np_array(x):
    import numpy as np

    return np.array([x])


def start_stop(ax, m, cases, xmax, use_tau, args, np):
    """The start-stop limit of the trailing edge (one-segment maps, w1/v <= 1e-3)."""
    ref = [i for i in cases if m["scales"]["time"][i] > 0 and (
        args.start_stop == "on" or
        (args.start_stop == "auto" and m["v1_over_v"][i] <= 1e-3 and m["K"] == 1))]
    for tau_ref in sorted({1.0 if use_tau else float(m["scales"]["time"][i]) for i in ref}):
        xr = np.linspace(0, xmax, 400)
        ax.plot(xr, (1 - np.exp(-xr / tau_ref)) ** 0.5, color="black", lw=1.2, ls="-.", zorder=5)
    far = [i for i in ref if m["zeta1"][i] > 1 or m["zeta"][i] < 1]
    if far:
        many = len(far) > 1
        listed = ", ".join(map(str, far[:MAX_LISTED])) + (" ..." if len(far) > MAX_LISTED else "")
        msg = (f"the start-stop limit needs v \u03c4 \u226b a\u2081 \u226b v\u2081 \u03c4;\n"
               f"case{'s' if many else ''} {listed} ha{'ve' if many else 's'} "
               f"\u03b6 < 1 or \u03b6\u2081 > 1")
        print(f"{PROG}: note: the start-stop limit needs v tau >> a1 >> v1 tau; "
              f"case{'s' if many else ''} {listed} ha{'ve' if many else 's'} "
              f"zeta < 1 or zeta1 > 1")
        ax.text(0.98, 0.5, msg, transform=ax.transAxes, fontsize=7.5, color="0.3",
                ha="right", va="center")
    ax.set_ylim(-0.03, 1.08)


def y_axis(ax, q, values, pre_levels, zoom, pre_len, args, np):
    """Log or linear y axis; with --zoom the range of t >= 0 and arrows for levels above it."""
    allv = np.concatenate([np.ravel(v) for v in values]) if values else np.array([])
    allv = allv[np.isfinite(allv)]
    pos = allv[allv > 0]
    log = False
    if np.any(allv < 0) or pos.size == 0:
        if args.ylog == "on":
            print(f"{PROG}: note: {q} has negative or no positive values; linear y axis")
    elif args.ylog == "on":
        log = True
    elif args.ylog == "auto":
        log = pos.max() / pos.min() > 100
    if zoom and allv.size:
        lo, hi = float(allv.min()), float(allv.max())
        if log:
            lo, hi = float(pos.min()), float(pos.max())
            pad = (hi / lo) ** 0.06
            ax.set_ylim(lo / pad, hi * pad)
        else:
            pad = 0.08 * (hi - lo) or 0.1 * abs(hi) or 1.0
            ax.set_ylim(lo - pad, hi + pad)
        top = ax.get_ylim()[1]
        for k, (c, yp) in enumerate([(c, yp) for c, yp in pre_levels if yp > top]):
            ax.annotate(f"\u2191{fmt(yp)}", xy=(-1.5 * pre_len, top), xycoords="data",
                        xytext=(2, -9 - 10 * k), textcoords="offset points", ha="left",
                        va="center", fontsize=7, color=c)
    if log:
        ax.set_yscale("log")
        if pos.size < allv.size:
            ax.text(0.98, 0.5, "values = 0 are not shown on the log axis",
                    transform=ax.transAxes, fontsize=7.5, color="0.3", ha="right")


def panel(ax, m, q, cases, colours, xs, xmax, use_tau, args, np):
    pre_len = 0.08 * xmax
    values, pre_levels = [], []  # pre_levels: (colour, level) left out of the range by --zoom
    zoom = args.zoom and m["schema"][f"timeseries/{q}"][0] == "force"
    for c, i in zip(colours, cases):
        draw_case(ax, m, q, i, c, xs, xmax, pre_len, args, values, pre_levels, zoom)
    if q == "a2":
        start_stop(ax, m, cases, xmax, use_tau, args, np)
    else:
        y_axis(ax, q, values, pre_levels, zoom, pre_len, args, np)
    title, ylabel = labels(m, q, args)
    ax.set_title(f"({'abcdefghij'[m['quant'].index(q)]}) {title}", fontsize=11, loc="left")
    ax.set_ylabel(ylabel)
    ax.axvline(0, color="0.6", lw=0.6, zorder=0)
    ax.grid(True, alpha=0.25)
    ax.set_xlim(-1.5 * pre_len, xmax)


def legends(fig, m, cases, colours, args):
    """The cases and the line styles below the panels; the space they take."""
    from matplotlib.lines import Line2D

    grey = "0.35"
    style = [(Line2D([], [], color=grey, lw=1.6), "mdrmap (t < 0: stationary level before t = 0"
              + ("; \u2191value: that level, above the axis)" if args.zoom else ")")),
             (Line2D([], [], color=grey, marker="o", mfc="none", ls="none", ms=8),
              "analytic estimate at t = 0+ (eqs. 15, 16; fixed depth)"),
             (Line2D([], [], color=grey, lw=1.0, ls="--"),
              "analytic stationary level of the last segment"),
             (Line2D([], [], color="black", lw=1.2, ls="-."),
              "start-stop limit a2 = a1 (1 \u2212 exp(\u2212t/\u03c4))^(1/2)")]
    max_rows = 14
    handles = [Line2D([], [], color=c, lw=2) for c in colours][:max_rows]
    names = [f"case {i}: {case_params(m, i)}" for i in cases][:max_rows]
    if len(cases) > max_rows:
        names[-1] = f"... and {len(cases) - max_rows + 1} more cases"
    fig.add_artist(fig.legend(handles, names, loc="lower left", bbox_to_anchor=(0.01, 0.0),
                              fontsize=8, frameon=False, title="cases", title_fontsize=8.5))
    fig.legend([h for h, _ in style], [t for _, t in style], loc="lower right",
               bbox_to_anchor=(0.99, 0.0), fontsize=8, frameon=False, title="lines",
               title_fontsize=8.5)
    return max(min(len(cases), max_rows), len(style)) + 1


def figure(m, cases, args, np):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    use_tau = all(m["scales"]["time"][i] > 0 for i in cases)
    xs = {i: m["ts"]["t"][i] / m["scales"]["time"][i] if use_tau else m["ts"]["t"][i]
          for i in cases}
    xmax = args.t_max or max(float(np.nanmax(xs[i])) for i in cases)
    xmax = xmax if xmax > 0 else 1.0
    if len(cases) <= 10:
        colours = [plt.get_cmap("tab10")(k) for k in range(len(cases))]
    else:
        colours = [plt.get_cmap("viridis")(k / (len(cases) - 1)) for k in range(len(cases))]
    nrows = math.ceil(len(m["quant"]) / 2)
    fig, axes = plt.subplots(nrows, 2, figsize=(12, 4.2 * nrows), sharex=True, squeeze=False)
    axes = axes.ravel()
    for ax in axes[len(m["quant"]):]:
        ax.set_visible(False)
    for ax, q in zip(axes, m["quant"]):
        panel(ax, m, q, cases, colours, xs, xmax, use_tau, args, np)
    for ax in axes[len(m["quant"]) - 2:len(m["quant"])]:
        ax.set_xlabel("t / \u03c4" if use_tau else "t  (a plotted case has \u03c4 = 0)")
    n_rows = legends(fig, m, cases, colours, args)
    title = args.title or ("Response to the velocity history (cf. seed paper, Fig. 2)"
                           + (", in the map's scales" if args.scaled else ""))
    fig.suptitle(f"{title}\n{os.path.basename(args.map)}", fontsize=11)
    fig.tight_layout(rect=(0, min(0.42, (0.004 + 0.019 * n_rows) * 2 / nrows), 1, 0.95))
    return fig


def main(argv=None):
    args = build_parser().parse_args(argv)
    if args.dpi <= 0 or args.dpi > 1200:
        raise UserError(f"--dpi {args.dpi}: must be in 1..1200")
    if args.t_max is not None and not (args.t_max > 0 and math.isfinite(args.t_max)):
        raise UserError(f"--t-max {args.t_max}: must be a positive number")

    import numpy as np
    import h5py

    m = load(args.map, np, h5py)
    cases, notes = choose_cases(args, m, np)
    for note in notes:
        print(f"{PROG}: {note}")
    output = args.output or (os.path.splitext(os.path.basename(args.map))[0] + "_timeseries.png")
    outdir = os.path.dirname(os.path.abspath(output))
    if not os.path.isdir(outdir):
        raise UserError(f"cannot write {output}: no such directory {outdir}")
    fig = figure(m, cases, args, np)
    save_figure(fig, output, args.dpi)
    print(f"{PROG}: wrote {output} ({len(cases)} case{'s' if len(cases) != 1 else ''})")
    return 0


if __name__ == "__main__":
    sys.exit(run_tool(main, PROG))
