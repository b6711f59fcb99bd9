# pyrun-needs: numpy matplotlib mdrmap
"""Velocity-step responses under load (or at fixed depth), with a table of
the rate-and-state numbers: computes the runs with
mdrmap.simulate in this process (or reads CSVs of `mdrmap simulate`) and
plots friction and depth against slip.

For each zeta0 = v0 tau / a0 (a0 the Hertz radius of F0; a1 the leading edge at
fixed depth) the tool runs a step up (v0 -> RATIO v0) and a step down
(v0 -> v0 / RATIO) out of stationary sliding at v0. The segment after the step
lasts max(30 tau, 30 a0 / v_after), long enough to settle, sampled on a log
scale (6 decades). Per run it prints, in units of a0/R for mu:

  mu_pre   stationary mu at v0 (the '# pre' line)
  jump     mu(0+) - mu_pre, the direct response to the step (without a
           parallel dashpot, --prony with --tau 0: mu_peak - mu_pre, the
           convention of mdrmap's event metrics, docs/design.md)
  mu_end   mu at the segment's end (the new stationary state)
  D_c      slip over which |mu - mu_end| falls to 1/e of |mu(0+) - mu_end|,
           in units of a0 (linear interpolation between samples)
  a        jump / ln(v_after / v0), the apparent direct effect
  a-b      (mu_end - mu_pre) / ln(v_after / v0)
  b        a - (a - b)
  d_end    depth at the end / d0, d0 = a0^2 / R (load control only)

The figure: mu/(a0/R) (top) and d/d0 (bottom, load control) against slip/a0
since the step (log scale), step up left, step down right, one colour per
zeta0; the dotted lines are the levels before the step.

With --prony G1:TAU1,... the material has a relaxation spectrum, as with
`mdrmap simulate --prony` (--G its long-term modulus, --tau the parallel
dashpot's time, 0 for none); tau above is then the case's time scale
(mdrmap's Result.scales["time"]).

Usage:
    python3 -m mdrmap steps --F0 0.0533 --R 100 -o steps.png
    python3 -m mdrmap steps --F0 0.0533 --csv-dir runs --from-csv -o steps.png
    python3 -m mdrmap steps --F0 0.0533 --tau 0 --prony 1:1,1:0.01 -o steps.png

Exit codes: 0 success, 2 bad input or a run mdrmap refuses or cannot compute
(one line on stderr).
"""

import argparse
import math
import sys

from ._maplib import Parser, UserError, run_tool, save_figure
from . import _runs as runs_io

PROG = "steps"


def parse_list(text, name):
    try:
        xs = [float(x) for x in text.split(",")]
    except ValueError:
        raise UserError(f"--{name}: must be a comma list of numbers, got {text!r}") from None
    if not xs or any(not (math.isfinite(x) and x > 0) for x in xs):
        raise UserError(f"--{name}: every value must be a finite number > 0, got {text!r}")
    return xs


def one_over_e_slip(slip, mu, mu_end):
    """Slip where |mu - mu_end| first falls to 1/e of its value at slip[0]; nan if never."""
    dev = abs(mu - mu_end)
    if not dev[0] > 0:
        return math.nan
    target = dev[0] / math.e
    for i in range(1, len(dev)):
        if dev[i] <= target:
            f = (dev[i - 1] - target) / (dev[i - 1] - dev[i])
            return slip[i - 1] + f * (slip[i] - slip[i - 1])
    return math.nan


def measure(run, ratio_log, np):
    """The table's numbers of one step run, scaled."""
    a, d_ref, mu_ref = run.scales()
    seg = run.segment(0)
    t, mu = run.col["t"][seg], run.col["mu"][seg]
    w = run.history()[0][0]
    mu_pre, mu0, mu_end = run.pre["mu"], mu[0], mu[-1]
    if run.case.get("tau") == 0 and run.events and "mu_peak" in run.events[0]:
        mu0 = run.events[0]["mu_peak"]  # no parallel dashpot: the direct effect is the peak
    m = {"mu_pre": mu_pre / mu_ref, "jump": (mu0 - mu_pre) / mu_ref, "mu_end": mu_end / mu_ref,
         "D_c": one_over_e_slip(w * t, mu, mu_end) / a}
    m["a"] = m["jump"] / ratio_log
    m["a-b"] = (m["mu_end"] - m["mu_pre"]) / ratio_log
    m["b"] = m["a"] - m["a-b"]
    m["d_end"] = run.col["d"][seg][-1] / d_ref if run.load else math.nan
    # the run must have settled: the last tenth of the slip changes mu by little
    late = w * t >= 0.9 * w * t[-1]
    m["settle"] = float(np.ptp(mu[late]) / max(abs(mu_end), 1e-300))
    return m


def plot(runs, zetas, a, output, dpi, load):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = 2 if load else 1
    fig, axes = plt.subplots(rows, 2, figsize=(10, 3.6 * rows), squeeze=False, sharex="col")
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for j, direction in enumerate(("up", "down")):
        for i, z in enumerate(zetas):
            run = runs[(z, direction)]
            ascale, d_ref, mu_ref = run.scales()
            seg = run.segment(0)
            w = run.history()[0][0]
            slip = w * run.col["t"][seg] / ascale
            pos = slip > 0
            c = colors[i % len(colors)]
            quantities = [("mu", mu_ref, run.pre["mu"])]
            if load:
                quantities.append(("d", d_ref, run.pre["d"]))
            for r, (q, ref, pre) in enumerate(quantities):
                ax = axes[r][j]
                ax.plot(slip[pos], run.col[q][seg][pos] / ref, color=c,
                        label=f"zeta0 = {z:g}")
                ax.plot([slip[pos][0]], [run.col[q][seg][0] / ref], "o", color=c, ms=3)
                ax.axhline(pre / ref, color=c, ls=":", lw=0.8)
        ratio = runs[(zetas[0], direction)].history()[0][0] / runs[(zetas[0], direction)].case["v"]
        axes[0][j].set_title(f"step {direction}: v -> {ratio:g} v")
        axes[0][j].set_ylabel("mu / (a0/R)" if load else "mu / a1/R")
        if load:
            axes[1][j].set_ylabel("d / d0")
        axes[-1][j].set_xlabel("slip since the step / a0" if load else "slip / a1")
        for ax in axes[:, j]:
            ax.set_xscale("log")
            ax.grid(True, which="both", alpha=0.3)
    axes[0][0].legend(fontsize=8)
    fig.suptitle("Velocity steps " + ("under load (F_N = F0)" if load else "at fixed depth")
                 + "; dotted: level before the step, dot: just after it", fontsize=10)
    fig.tight_layout()
    save_figure(fig, output, dpi)


def main(argv=None):
    p = Parser(prog=PROG, description=__doc__.split("\n\n")[0],
               formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    runs_io.add_common(p)
    p.add_argument("--zeta0", default="0.1,1,10", help="v0 tau / a0 values (default 0.1,1,10)")
    p.add_argument("--ratio", type=float, default=10.0, help="step factor (default 10)")
    a = p.parse_args(argv)
    runs_io.check_common(a)
    zetas = parse_list(a.zeta0, "zeta0")
    if not (math.isfinite(a.ratio) and a.ratio > 1):
        raise UserError(f"--ratio: must be a finite number > 1, got {a.ratio:g}")
    case = runs_io.case_kwargs(a)
    import numpy as np

    # the case's scales (mdrmap's), to choose the velocities; --from-csv reads
    # each run with its own
    sc = None if a.from_csv else runs_io.probe_scales(a)
    runs = {}
    for z in zetas:
        for direction in ("up", "down"):
            kwargs = None
            if sc is not None:
                scale, time = sc["length"], sc["time"]
                v0 = z * scale / time
                w = v0 * a.ratio if direction == "up" else v0 / a.ratio
                T = max(30.0 * time, 30.0 * scale / w)
                kwargs = dict(case, v=v0, history=[(w, T)], samples=a.samples, spacing="log",
                              log_decades=6, rtol=a.rtol)
            runs[(z, direction)] = runs_io.obtain(a, f"step_{direction}_{z:g}.csv", kwargs, np,
                                                 PROG)
    scale = runs[(zetas[0], "up")].sc["length"]
    load = a.F0 is not None
    unit = "a0/R" if load else "a1/R"
    cols = ["mu_pre", "jump", "mu_end", "D_c", "a", "a-b", "b", "d_end", "settle"]
    print(f"# mu-like columns in units of {unit}, D_c in units of {'a0' if load else 'a1'}, "
          f"d_end of d0; settle = spread of mu over the last tenth of the slip / mu_end")
    print("zeta0  step  " + "  ".join(f"{c:>10}" for c in cols))
    for z in zetas:
        for direction in ("up", "down"):
            m = measure(runs[(z, direction)], math.log(a.ratio if direction == "up"
                                                       else 1 / a.ratio), np)
            print(f"{z:<6g} {direction:<5} " + "  ".join(f"{m[c]:>10.4g}" for c in cols))
    if a.output:
        plot(runs, zetas, scale, a.output, a.dpi, load)
        print(f"wrote {a.output}")
    return 0


if __name__ == "__main__":
    sys.exit(run_tool(main, PROG))
