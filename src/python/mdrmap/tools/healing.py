# pyrun-needs: numpy matplotlib mdrmap
"""Healing in slide-hold-slide tests under load (or at fixed depth): runs
mdrmap.simulate in this process (or reads CSVs of `mdrmap simulate`) for a
range of hold times and plots the friction peak after the reslide against
log10(hold time).

Each run slides stationarily at v0 (zeta0 = v0 tau / a0, a0 the Hertz radius
of F0; a1 the leading edge at fixed depth: mdrmap's scales of the case, from
Result.scales of a short run of the case), holds (velocity 0) for t_hold, then
slides again at v0 for max(20 tau, 20 a0 / v0), each segment sampled on a log
scale (6 decades). dmu_peak = the largest mu of the reslide (its event's
mu_max, from the solver's solution) minus the
stationary mu at v0 (the '# pre' line), in units of a0/R. The tool prints
dmu_peak per hold, its change per decade of hold time between neighbouring
holds, and the least-squares slope d(dmu_peak)/d(log10 t_hold) over all holds.

The figure: dmu_peak/(a0/R) against log10(t_hold/tau) (left), and mu/(a0/R)
against slip/a0 during the reslide for each hold (right, the middle zeta0
of the list).

With --prony G1:TAU1,... the material has a relaxation spectrum, as with
`mdrmap simulate --prony` (--G its long-term modulus, --tau the parallel
dashpot's time, 0 for none); tau above is then the case's time scale
(mdrmap's Result.scales["time"]).

Usage:
    python3 -m mdrmap healing --F0 0.0533 --R 100 -o healing.png
    python3 -m mdrmap healing --F0 0.0533 --holds 0.1,1,10 --zeta0 1 -o h.png
    python3 -m mdrmap healing --d 0.01 --tau 0 --prony 1:1,1:0.01 -o h.png

Exit codes: 0 success, 2 bad input or a run mdrmap refuses or cannot compute
(one line on stderr).
"""

import argparse
import math
import sys

from ._maplib import Parser, UserError, run_tool, save_figure
from . import _runs as runs_io
from .steps import parse_list

PROG = "healing"


def default_holds():
    """0.1 .. 1000 tau, 9 holds, log spaced."""
    return [10 ** (-1 + 0.5 * k) for k in range(9)]


def peak(run):
    """(dmu_peak, slip of the peak) of the reslide (segment 1), scaled by a0/R and
    a0: its event's mu_max and slip_max (the largest mu on the solver's solution,
    not of the samples), or, from an mdrmap before them, the largest sample."""
    a, _, mu_ref = run.scales()
    event = run.events[1] if len(run.events) > 1 else {}
    if "mu_max" in event:
        return (event["mu_max"] - run.pre["mu"]) / mu_ref, event["slip_max"] / a
    seg = run.segment(1)
    mu, t = run.col["mu"][seg], run.col["t"][seg]
    i = int(mu.argmax())
    w = run.history()[1][0]
    return (mu[i] - run.pre["mu"]) / mu_ref, w * (t[i] - t[0]) / a


def plot(runs, zetas, holds, output, dpi, load, np):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(10.5, 4))
    for z in zetas:
        y = [peak(runs[(z, h)])[0] for h in holds]
        ax.plot(np.log10(holds), y, "o-", label=f"zeta0 = {z:g}")
    ax.set_xlabel("log10(t_hold / tau)")
    ax.set_ylabel("dmu_peak / (a0/R)" if load else "dmu_peak / a1/R")
    ax.set_title("peak of mu after the reslide above steady")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    cmap = plt.get_cmap("viridis")
    z = zetas[len(zetas) // 2]
    for k, h in enumerate(holds):
        run = runs[(z, h)]
        a, _, mu_ref = run.scales()
        seg = run.segment(1)
        w = run.history()[1][0]
        slip = w * (run.col["t"][seg] - run.col["t"][seg][0]) / a
        pos = slip > 0
        bx.plot(slip[pos], run.col["mu"][seg][pos] / mu_ref, color=cmap(k / max(1, len(holds) - 1)),
                label=f"{h:.3g} tau")
    bx.axhline(runs[(z, holds[0])].pre["mu"] / runs[(z, holds[0])].scales()[2], color="k",
               ls=":", lw=0.8)
    bx.set_xscale("log")
    bx.set_xlabel("slip since the reslide / a0" if load else "slip / a1")
    bx.set_ylabel("mu / (a0/R)" if load else "mu / a1/R")
    bx.set_title(f"reslides at zeta0 = {z:g} (dotted: steady)")
    bx.grid(True, which="both", alpha=0.3)
    bx.legend(fontsize=7, title="hold", title_fontsize=7)
    fig.suptitle("Slide-hold-slide " + ("under load (F_N = F0)" if load else "at fixed depth"),
                 fontsize=10)
    fig.tight_layout()
    save_figure(fig, output, dpi)


def main(argv=None):
    p = Parser(prog=PROG, description=__doc__.split("\n\n")[0],
               formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    runs_io.add_common(p)
    p.add_argument("--zeta0", default="1", help="v0 tau / a0 values (default 1)")
    p.add_argument("--holds", help="hold times in units of tau (default 9 from 0.1 to 1000, "
                                   "log spaced)")
    a = p.parse_args(argv)
    runs_io.check_common(a)
    zetas = parse_list(a.zeta0, "zeta0")
    holds = parse_list(a.holds, "holds") if a.holds else default_holds()
    if len(set(holds)) != len(holds) or sorted(holds) != holds:
        raise UserError(f"--holds: must increase, got {a.holds}")
    case = runs_io.case_kwargs(a)
    import numpy as np

    # the case's scales (mdrmap's), to choose the velocities; --from-csv reads
    # each run with its own
    sc = None if a.from_csv else runs_io.probe_scales(a)
    runs = {}
    for z in zetas:
        for h in holds:
            kwargs = None
            if sc is not None:
                scale, time = sc["length"], sc["time"]
                v0 = z * scale / time
                T = max(20.0 * time, 20.0 * scale / v0)
                kwargs = dict(case, v=v0, history=[(0.0, h * time), (v0, T)], samples=a.samples,
                              spacing="log", log_decades=6, rtol=a.rtol)
            runs[(z, h)] = runs_io.obtain(a, f"shs_{z:g}_{h:.6g}.csv", kwargs, np, PROG)
    load = a.F0 is not None
    unit = "a0/R" if load else "a1/R"
    print(f"# dmu_peak in units of {unit}, slip_peak of {'a0' if load else 'a1'}; "
          f"per_decade = change of dmu_peak from the previous hold / decades between them")
    for z in zetas:
        y = [peak(runs[(z, h)]) for h in holds]
        print(f"zeta0 = {z:g}")
        print(f"{'t_hold/tau':>12} {'dmu_peak':>12} {'slip_peak':>12} {'per_decade':>12}")
        for k, h in enumerate(holds):
            per = ((y[k][0] - y[k - 1][0]) / math.log10(h / holds[k - 1])) if k else math.nan
            print(f"{h:>12.4g} {y[k][0]:>12.5g} {y[k][1]:>12.4g} {per:>12.5g}")
        if len(holds) >= 2:
            slope = np.polyfit(np.log10(holds), [v[0] for v in y], 1)[0]
            print(f"slope d(dmu_peak)/d(log10 t_hold) over all holds: {slope:.5g}")
    if a.output:
        plot(runs, zetas, holds, a.output, a.dpi, load, np)
        print(f"wrote {a.output}")
    return 0


if __name__ == "__main__":
    sys.exit(run_tool(main, PROG))
