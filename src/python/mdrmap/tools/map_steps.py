# pyrun-needs: numpy matplotlib h5py
"""Step responses in scaled variables from an mdrmap-map/2 map with time series.

For event K (default 0; event k is the change at the start of segment k + 1,
from w_before = w_k (v for k = 0) to w_after = w_(k+1)) and the chosen cases,
plots against the slip since the change, w_after (t - events/t[:, K]), over
the map's length scale (/scales/length: the Hertz radius a0 under load, the
leading edge a1 at fixed depth; mu over /scales/friction, a/R):

  left   the normalised response
         (mu - mu_ss(w_before)) / (mu_ss(w_after) - mu_ss(w_before)),
         0 = the stationary friction before, 1 = the stationary friction after
         (analytic/mu_pre for K = 0, else analytic/mu_ss[:, K-1]; and
         analytic/mu_ss[:, K]); cases with equal stationary values are left out;
  right  mu / (a/R) against slip / a, with the stationary levels before
         (dotted) and after (dashed).

The slip axis is logarithmic (samples at zero slip are not drawn). An event
into a hold (w_after = 0) has no slip: those cases are skipped.

Cases: every done case (default), `--cases 0,3,5` (0-based rows of the map),
or `--select AXIS=VALUE` (repeatable; the grid value nearest to VALUE of a
grid axis such as v, F0, w1_over_v, T1_over_tau; the tool says which).
Prints one row per plotted case: its zeta0 = v tau / a0 (zeta = v tau / a1 at
depth), w_after / w_before, the stationary levels and mu just after the change
in units of a/R, the normalised response just after the change and at the
segment's end, and D_c (events/D_c) in units of a.

Usage:
    python3 -m mdrmap map_steps velocity_steps.h5 -o steps.png
    python3 -m mdrmap map_steps velocity_steps.h5 --event 1 --select v=0.1 -o steps.png
    python3 -m mdrmap map_steps seed_step.h5 --select tau=2,w1_over_v=0.01 -o drop.png

Exit codes: 0 success, 2 bad input (one line on stderr).
"""

import math
import os
import sys

from ._maplib import (UserError, add_figure_options, add_select_option, fmt,
                    map_tool_parser, open_map2, parse_map_tool_args, read_masked, run_tool,
                    save_figure, select_cases)

PROG = "map_steps"
MAX_LEGEND = 12


def read_event(f, m, k, path, np):
    """Event k's samples and metrics: {"t", "mu" (the segment's time series),
    "before", "after" (stationary mu), "t0", "dc", "mu_after"}."""
    n, K = m["n"], m["K"]
    if any(f"timeseries/{q}" not in f for q in ("t", "mu", "segment")):
        raise UserError(f"{path} has no /timeseries: rerun the study with "
                        f"timeseries = true in [run] (or --set run.timeseries=true)")
    if not 0 <= k < K:
        raise UserError(f"--event {k}: the map has {K} event(s) (0..{K - 1})")
    for need in ("analytic/mu_pre", "analytic/mu_ss", "events/t", "events/D_c",
                 "events/mu_after"):
        if need not in f:
            raise UserError(f"{path} is an incomplete mdrmap map (no /{need})")
    seg = np.asarray(f["timeseries/segment"][()]).astype(int)
    cols = np.flatnonzero(seg == k)
    if cols.size == 0:
        raise UserError(f"{path}: /timeseries/segment has no sample of segment {k}")
    lo, hi = int(cols.min()), int(cols.max()) + 1
    ss = read_masked(f["analytic/mu_ss"]).reshape(n, K)
    per_event = {q: read_masked(f[f"events/{q}"]).reshape(n, K)[:, k]
                 for q in ("t", "D_c", "mu_after")}
    return {"t": np.asarray(f["timeseries/t"][:, lo:hi], dtype=float)[:, cols - lo],
            "mu": np.asarray(f["timeseries/mu"][:, lo:hi], dtype=float)[:, cols - lo],
            "before": read_masked(f["analytic/mu_pre"]) if k == 0 else ss[:, k - 1],
            "after": ss[:, k], "t0": per_event["t"], "dc": per_event["D_c"],
            "mu_after": per_event["mu_after"]}


def wanted_cases(args, sel, m, np):
    """(keep [N], notes): --cases and --select."""
    n, notes = m["n"], []
    keep = np.ones(n, dtype=bool)
    if args.cases:
        try:
            wanted = [int(s) for s in args.cases.split(",") if s.strip()]
        except ValueError:
            raise UserError(f"--cases {args.cases!r}: expected case numbers, e.g. 0,3,5") from None
        for i in wanted:
            if not 0 <= i < n:
                raise UserError(f"--cases {i}: the map has {n} cases (0..{n - 1})")
        keep[:] = False
        keep[wanted] = True
    if sel:
        ks, sn = select_cases(m, sel, np)
        keep &= ks
        notes += sn
    return keep, notes


def plotted_cases(args, sel, m, ev, k, np):
    """(idx, same, w_before, w_after, notes): the done, chosen cases whose event
    k does not start a hold; same: those with equal stationary levels."""
    keep, notes = wanted_cases(args, sel, m, np)
    done = m["status"] == 1
    n_nd = int(np.sum(keep & ~done))
    if n_nd:
        notes.append(f"skipped {n_nd} case(s) not done (failed or pending)")
    keep &= done
    w_before = m["cols"]["v"] if k == 0 else m["w"][:, k - 1]
    w_after = m["w"][:, k]
    hold = keep & ~(w_after > 0)
    if hold.any():
        notes.append(f"skipped {int(hold.sum())} case(s) where event {k} starts a hold "
                     f"(w = 0: no slip)")
    keep &= w_after > 0
    if not keep.any():
        if hold.any():
            raise UserError(f"event {k} starts a hold (w = 0) in every chosen case: no slip to "
                            f"plot against (choose another --event)")
        raise UserError(f"{args.map}: no done case among the chosen ones")
    before, after = ev["before"], ev["after"]
    same = keep & ~(np.abs(after - before) > 1e-12 * np.maximum(np.abs(after), np.abs(before)))
    if same.any():
        notes.append(f"{int(same.sum())} case(s) with mu_ss(w_after) = mu_ss(w_before) left out "
                     f"of the normalised panel")
    return np.flatnonzero(keep), same, w_before, w_after, notes


def draw(ax, bx, plt, m, ev, chosen):
    """The curves, in the map's scales (/scales/length, /scales/friction); the rows."""
    idx, same, w_before, w_after, _ = chosen
    a, ms, before, after = m["a"], m["mu_scale"], ev["before"], ev["after"]
    if len(idx) <= 10:
        colours = [plt.get_cmap("tab10")(j) for j in range(len(idx))]
    else:
        colours = [plt.get_cmap("viridis")(j / (len(idx) - 1)) for j in range(len(idx))]
    rows = []
    for col, i in zip(colours, idx):
        slip = w_after[i] * (ev["t"][i] - ev["t0"][i]) / a[i]
        pos = slip > 0
        ratio = w_after[i] / w_before[i] if w_before[i] > 0 else math.inf
        lab = f"case {i}: {m['zeta_name']}={fmt(m['zeta'][i])}, w ratio {fmt(ratio)}"
        norm = math.nan, math.nan
        if not same[i]:
            y = (ev["mu"][i] - before[i]) / (after[i] - before[i])
            ax.plot(slip[pos], y[pos], "-", color=col, lw=1.4, label=lab)
            norm = (float((ev["mu_after"][i] - before[i]) / (after[i] - before[i])), float(y[-1]))
        bx.plot(slip[pos], ev["mu"][i][pos] / ms[i], "-", color=col, lw=1.4, label=lab)
        bx.axhline(before[i] / ms[i], color=col, lw=0.8, ls=":")
        bx.axhline(after[i] / ms[i], color=col, lw=0.8, ls="--")
        rows.append((int(i), m["zeta"][i], ratio, before[i] / ms[i], after[i] / ms[i],
                     ev["mu_after"][i] / ms[i], norm[0], norm[1], ev["dc"][i] / a[i]))
    return rows


def figure(m, ev, chosen, k, args):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(12, 5))
    rows = draw(ax, bx, plt, m, ev, chosen)
    for axis in (ax, bx):
        axis.set_xscale("log")
        axis.set_xlabel(f"slip since the change / {m['a_name']}")
        axis.grid(True, which="both", alpha=0.3)
    ax.axhline(0, color="0.4", lw=0.8)
    ax.axhline(1, color="0.4", lw=0.8)
    ax.set_ylabel("(\u03bc \u2212 \u03bc$_{ss}$(w$_{before}$)) / "
                  "(\u03bc$_{ss}$(w$_{after}$) \u2212 \u03bc$_{ss}$(w$_{before}$))")
    ax.set_title("normalised response: 0 before, 1 after", fontsize=10)
    bx.set_ylabel(f"\u03bc / ({m['a_name']}/R)")
    bx.set_title("friction; dotted: stationary before, dashed: after", fontsize=10)
    n = len(rows)
    if n <= MAX_LEGEND:
        bx.legend(fontsize=7.5)
    fig.suptitle(args.title or (f"{os.path.basename(args.map)}: responses to event {k} "
                                f"(start of segment {k + 1}) "
                                + ("under load" if m["loading"] == "force" else "at fixed depth")
                                + f", {n} case{'s' if n != 1 else ''}"), fontsize=11)
    fig.tight_layout()
    return fig, rows


def report(m, rows, k):
    a_name, zname = m["a_name"], m["zeta_name"]
    print(f"event {k}: {len(rows)} case(s); mu in units of {a_name}/R, D_c in units of {a_name}")
    print(f"{'case':>5} {zname:>9} {'w ratio':>9} {'mu_ss before':>13} {'mu_ss after':>12} "
          f"{'mu after':>10} {'norm 0+':>9} {'norm end':>9} {'D_c':>10}")
    for i, z, r, b, af, m0, n0, n1, d in rows:
        print(f"{i:>5} {z:>9.4g} {r:>9.4g} {b:>13.6g} {af:>12.6g} {m0:>10.6g} {n0:>9.4g} "
              f"{n1:>9.4g} {d:>10.4g}")


def main(argv=None):
    ap = map_tool_parser(PROG, __doc__, "mdrmap-map/2 map (.h5) written with timeseries = true",
                         "_steps.png")
    ap.add_argument("--event", type=int, default=0, metavar="K",
                    help="0-based event: the change at the start of segment K+1 (default 0)")
    ap.add_argument("--cases", default=None, metavar="I,J,...",
                    help="0-based case rows to plot (default: every done case)")
    add_select_option(ap)
    add_figure_options(ap)
    args, sel, output = parse_map_tool_args(ap, argv)

    import numpy as np

    f, m = open_map2(args.map, np, PROG)
    with f:
        ev = read_event(f, m, args.event, args.map, np)
    chosen = plotted_cases(args, sel, m, ev, args.event, np)
    fig, rows = figure(m, ev, chosen, args.event, args)
    for note in chosen[-1]:
        print(f"{PROG}: {note}")
    report(m, rows, args.event)
    save_figure(fig, output, args.dpi)
    print(f"{PROG}: wrote {output}")
    return 0


if __name__ == "__main__":
    sys.exit(run_tool(main, PROG))
