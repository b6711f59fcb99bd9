# pyrun-needs: numpy matplotlib mdrmap
"""One run of mdrmap: the friction coefficient mu and the normal force FN (the
depth d under load) against time t or slip, from mdrmap.simulate arguments or
from a CSV that `mdrmap simulate --output` wrote.

The run is either computed here, by mdrmap.simulate in this process, from its
keyword arguments given as KEY=VALUE (the keywords of help(mdrmap.simulate):
d or F0, R, tau, G, v, history as W1:T1,W2:T2,..., v1, t_end, prony as
G1:TAU1,..., samples, spacing, rtol, ...; values as the command line takes
them), or read with --csv from a CSV of `mdrmap simulate` (or one that
`python -m mdrmap steps/healing --csv-dir` kept).

The figure: mu (top) and FN at fixed depth, d under load (bottom) against t
(--x t, the default: time since the first velocity change) or the slip (--x
slip: the integral of the sliding velocity since t = 0); dotted: the
stationary state before t = 0 (the CSV's `# pre` line), grey lines: the
velocity changes. --scaled divides by the case's scales (the CSV's `# scales`
line, Result.scales): mu by the friction scale a/R, FN by the force scale, d
by the depth scale, t by the time scale, the slip by the length scale. The
tool prints the run's events (mu before and after each change, mu_max, a,
a - b, D_c) in the units of mu and the slip.

Usage:
    python3 -m mdrmap plot_run F0=0.0533 R=100 tau=1 v=1 history=1:5,0:10,1:20 -o run.png
    python3 -m mdrmap plot_run d=0.01 R=100 tau=1 v=1 v1=10 --x slip --scaled -o run.png
    mdrmap simulate --d 0.01 --R 100 --tau 1 --v 1 --v1 10 --output run.csv
    python3 -m mdrmap plot_run --csv run.csv -o run.png

Exit codes: 0 success, 2 bad input or a run mdrmap refuses or cannot compute
(one line on stderr).
"""

import argparse
import os
import sys

from ._maplib import Parser, UserError, run_tool, save_figure
from . import _runs as runs_io

PROG = "plot_run"
EVENT_COLUMNS = ["k", "t", "w_before", "w_after", "mu_before", "mu_after", "mu_max", "a",
                 "a_minus_b", "D_c"]


def parse_keywords(items):
    """["KEY=VALUE", ...] as {key: "VALUE"} (mdrmap.simulate checks keys and values)."""
    out = {}
    for item in items:
        key, sep, value = item.partition("=")
        if not sep or not key or not value:
            raise UserError(f"not a KEY=VALUE argument of mdrmap.simulate, got {item!r}")
        key = key.lstrip("-").replace("-", "_")
        if key == "progress":
            raise UserError("progress is not a KEY=VALUE argument here (the tool runs one case)")
        if key in out:
            raise UserError(f"{key} given twice")
        out[key] = value
    return out


def slip_of(run, np):
    """The slip since t = 0 at every sample: sum of w T over the segments
    before, plus w (t - start) in the sample's segment."""
    hist = run.history()
    starts = np.concatenate([[0.0], np.cumsum([T for _, T in hist])])
    before = np.concatenate([[0.0], np.cumsum([w * T for w, T in hist])])
    seg = run.col["segment"].astype(int)
    if seg.size and (seg.min() < 0 or seg.max() >= len(hist)):
        raise UserError(f"{run.path}: a row's segment is not one of the history's "
                        f"{len(hist)} segments")
    w = np.array([w for w, _ in hist])
    return before[seg] + w[seg] * (run.col["t"] - starts[seg])


def figure(run, args, np):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sc = run.sc if args.scaled else {}
    div = lambda key: sc.get(key, 1.0)  # noqa: E731
    lower = "d" if run.load else "FN"
    x = run.col["t"] / div("time") if args.x == "t" else slip_of(run, np) / div("length")
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(7.5, 6), sharex=True)
    ax.plot(x, run.col["mu"] / div("friction"), color="C0")
    ax.axhline(run.pre["mu"] / div("friction"), color="C0", ls=":", lw=0.8)
    bx.plot(x, run.col[lower] / div("depth" if lower == "d" else "force"), color="C1")
    bx.axhline(run.pre[lower] / div("depth" if lower == "d" else "force"), color="C1", ls=":",
               lw=0.8)
    hist = run.history()
    change = 0.0
    for k in range(1, len(hist)):  # the velocity changes after the first (at t = 0)
        change += hist[k - 1][0] * hist[k - 1][1] if args.x == "slip" else hist[k - 1][1]
        for axis in (ax, bx):
            axis.axvline(change / div("length" if args.x == "slip" else "time"), color="0.6",
                         lw=0.7)
    ax.set_ylabel("mu / (a/R)" if args.scaled else "mu")
    bx.set_ylabel((lower + (" / depth scale" if lower == "d" else " / force scale"))
                  if args.scaled else lower)
    bx.set_xlabel(("t / time scale" if args.x == "t" else "slip / length scale") if args.scaled
                  else ("t" if args.x == "t" else "slip"))
    for axis in (ax, bx):
        axis.grid(True, alpha=0.3)
    ax.set_title(f"{os.path.basename(run.path)}: "
                 + ("under load (F0 = %g)" % run.case["F0"] if run.load
                    else "at fixed depth (d = %g)" % run.case["d"])
                 + "; dotted: stationary before t = 0", fontsize=9)
    fig.tight_layout()
    return fig


def main(argv=None):
    p = Parser(prog=PROG, description=__doc__.split("\n\n")[0],
               formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    p.add_argument("keywords", nargs="*", metavar="KEY=VALUE",
                   help="mdrmap.simulate's keyword arguments (e.g. F0=0.05 R=100 tau=1 v=1 "
                        "history=1:5,0:10,1:20)")
    p.add_argument("--csv", help="read the run from this CSV of `mdrmap simulate` instead")
    p.add_argument("--x", choices=("t", "slip"), default="t",
                   help="the horizontal axis: t (default) or slip")
    p.add_argument("--scaled", action="store_true", help="divide by the case's scales")
    p.add_argument("-o", "--output", default="run.png", help="the PNG (default run.png)")
    p.add_argument("--dpi", type=int, default=120, help="figure resolution (default 120)")
    args = p.parse_args(argv)
    if (args.csv is None) == (not args.keywords):
        raise UserError("give either mdrmap.simulate's KEY=VALUE arguments or --csv FILE "
                        "(one of them)")
    if os.path.isdir(args.output):
        raise UserError(f"-o: {args.output} is a directory")
    if args.dpi < 10:
        raise UserError(f"--dpi: must be an integer >= 10, got {args.dpi}")
    import numpy as np

    if args.csv is not None:
        run = runs_io.read_csv(args.csv, np)
    else:
        keywords = parse_keywords(args.keywords)
        run = runs_io.from_result(runs_io.run_simulate(keywords), "mdrmap.simulate")
    print(f"{PROG}: {run.col['t'].size} samples, {len(run.events)} events, "
          f"mu before t = 0: {run.pre['mu']:.6g}")
    print("  ".join(f"{c:>11}" for c in EVENT_COLUMNS))
    for e in run.events:
        print("  ".join(f"{e.get(c, float('nan')):>11.5g}" if c != "k"
                        else f"{int(e.get(c, -1)):>11d}" for c in EVENT_COLUMNS))
    fig = figure(run, args, np)
    save_figure(fig, args.output, args.dpi)
    print(f"{PROG}: wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(run_tool(main, PROG))
