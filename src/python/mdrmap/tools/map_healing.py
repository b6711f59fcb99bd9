# pyrun-needs: numpy matplotlib h5py
"""The healing curve of a slide-hold-slide mdrmap-map/2 map: the friction peak
after the reslide against the hold time.

The map must be a slide-hold-slide study: stationary sliding at v, segment 1 a
hold (/cases/w[:, 0] = 0) of duration T1 = /cases/T[:, 0], segment 2 the
reslide (w2 > 0), e.g. jobs/examples/shs_holds.ini. For every done case

    dmu_peak = events/mu_max[:, 1] - analytic/mu_pre  (the reslide's largest mu)

(the sample of the reslide farthest from the stationary friction at w2, minus
the stationary friction at v), in units of the map's friction scale
/scales/friction (a0/R under load, a0 the Hertz radius; a1/R at fixed depth, a1
the leading edge), is
plotted against T1 / tau (tau: /scales/time) on a log axis, one curve per value of the other
parameters that vary (labelled with zeta0 = v tau / a0, or zeta = v tau / a1,
and whatever else differs). The right panel shows the slip of the peak
(events/slip_max[:, 1]) in units of a0 (a1): /scales/length.

Prints, per curve, dmu_peak per hold with its change per decade of hold time
from the previous hold, and the least-squares slope d(dmu_peak)/d(log10 T1)
over all holds of the curve ("per decade"). Cases not done or with tau = 0 are
skipped and counted.

Usage:
    python3 -m mdrmap map_healing shs_holds.h5 -o healing.png
    python3 -m mdrmap map_healing shs_holds.h5 --select v=0.1 -o healing.png

Exit codes: 0 success, 2 bad input (one line on stderr).
"""

import math
import os
import sys

from ._maplib import (SELECT_HELP, UserError, add_figure_options, add_select_option,
                    fmt, map_tool_parser, open_map2, parse_map_tool_args, read_masked, run_tool,
                    save_figure, select_cases)

PROG = "map_healing"


def slope_per_decade(x, y, np):
    """Least-squares slope of y against log10 x (nan with fewer than 2 points)."""
    ok = np.isfinite(y) & (x > 0)
    if ok.sum() < 2:
        return math.nan
    return float(np.polyfit(np.log10(x[ok]), y[ok], 1)[0])


def check_shs(m, path, np):
    """UserError unless every done case is a slide-hold-slide (w1 = 0, w2 > 0)."""
    K, done, w = m["K"], m["status"] == 1, m["w"]
    if K >= 2 and done.any() and not np.any(w[done, 0] != 0) and np.all(w[done, 1] > 0):
        return
    what = (f"it has {K} segment" + ("s" if K != 1 else "")) if K < 2 else \
        ("no case is done" if not done.any() else
         ("segment 1 is not a hold (w1 != 0) in every case" if np.any(w[done, 0] != 0)
          else "segment 2 is not a reslide (w2 > 0) in every case"))
    raise UserError(f"{path} is not a slide-hold-slide map ({what}): this tool needs "
                    f"segment 1 a hold (w1 = 0) and segment 2 a reslide (w2 > 0)")


def read(args, sel, np):
    """(m, dmu, slip_a, hold, use, notes): the map's cases; the peak after the
    reslide over the stationary mu at v in the friction scale, its slip in the
    length scale, the hold T1 in the time scale (all /scales); the cases used."""
    f, m = open_map2(args.map, np, PROG)
    with f:
        check_shs(m, args.map, np)
        # the reslide's largest mu (events/mu_max; in maps without it mu_peak,
        # which was the sample farthest from mu_ss)
        which = "max" if "events/mu_max" in f else "peak"
        for need in (f"events/mu_{which}", f"events/slip_{which}", "analytic/mu_pre"):
            if need not in f:
                raise UserError(f"{args.map} is an incomplete mdrmap map (no /{need})")
        peak = read_masked(f[f"events/mu_{which}"]).reshape(m["n"], m["K"])[:, 1]
        slip = read_masked(f[f"events/slip_{which}"]).reshape(m["n"], m["K"])[:, 1]
        mu_pre = read_masked(f["analytic/mu_pre"])
    keep, notes = select_cases(m, sel, np)
    done, time = m["status"] == 1, m["scales"]["time"]
    n_nd = int(np.sum(keep & ~done))
    if n_nd:
        notes.append(f"skipped {n_nd} case(s) not done (failed or pending)")
    elastic = keep & done & ~(time > 0)
    if elastic.any():
        notes.append(f"skipped {int(elastic.sum())} case(s) with tau = 0 (no hold time scale)")
    use = keep & done & (time > 0)
    if not use.any():
        raise UserError(f"{args.map}: no done case with tau > 0 in the selection")
    with np.errstate(divide="ignore", invalid="ignore"):
        return (m, (peak - mu_pre) / m["mu_scale"], slip / m["a"], m["T"][:, 0] / time, use,
                notes)


def group_curves(m, use, hold, path, np):
    """[(label, cases by hold)]: one curve per value of everything but the hold
    time (the later segments by their velocity over v and duration over tau)."""
    c, K, w, time = m["cols"], m["K"], m["w"], m["scales"]["time"]

    def key(i):
        vals = [c[k][i] for k in c] + list(w[i, 1:] / c["v"][i]) + list(m["T"][i, 1:] / time[i])
        return tuple(float(f"{x:.12g}") for x in vals)
    names = list(c) + [f"w{k + 2}_over_v" for k in range(K - 1)] + \
        [f"T{k + 2}_over_tau" for k in range(K - 1)]
    curves = {}
    for i in np.flatnonzero(use):
        curves.setdefault(key(i), []).append(int(i))
    if max(len({hold[i] for i in v}) for v in curves.values()) < 2:
        raise UserError(f"{path} has one hold time per curve: no healing curve (the map needs "
                        f"several hold times T1)")
    keys = sorted(curves)
    varying = [j for j in range(len(names)) if len({k[j] for k in keys}) > 1]
    out = []
    for k in keys:
        idx = np.array(sorted(curves[k], key=lambda i: hold[i]))
        parts = [f"{m['zeta_name']}={fmt(m['zeta'][idx[0]])}"]
        parts += [f"{names[j]}={fmt(k[j])}" for j in varying if names[j] not in ("v", "tau")]
        out.append((", ".join(parts), idx))
    return out


def figure(m, curves, dmu, slip_a, hold, args, np):
    """The two panels; the rows report() prints."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.6))
    cmap = plt.get_cmap("tab10")
    rows = []
    for ci, (lab, idx) in enumerate(curves):
        x, y = hold[idx], dmu[idx]
        ax.plot(x, y, "o-", color=cmap(ci % 10), ms=4, label=lab)
        bx.plot(x, slip_a[idx], "o-", color=cmap(ci % 10), ms=4, label=lab)
        rows.append((lab, idx, x, y, slope_per_decade(x, y, np)))
    a_name = m["a_name"]
    for axis in (ax, bx):
        axis.set_xscale("log")
        axis.set_xlabel("hold time T$_1$ / \u03c4")
        axis.grid(True, which="both", alpha=0.3)
    ax.axhline(0, color="0.5", lw=0.8)
    ax.set_ylabel(f"\u0394\u03bc$_{{peak}}$ / ({a_name}/R)")
    ax.set_title("peak after the reslide \u2212 stationary \u03bc at v", fontsize=10)
    bx.set_ylabel(f"slip of the peak / {a_name}")
    bx.set_title("slip since the reslide at the peak", fontsize=10)
    ax.legend(fontsize=8)
    fig.suptitle(args.title or f"{os.path.basename(args.map)}: healing in slide-hold-slide "
                 + ("under load" if m["loading"] == "force" else "at fixed depth"), fontsize=11)
    fig.tight_layout()
    return fig, rows


def report(m, rows):
    a_name = m["a_name"]
    for lab, idx, x, y, s in rows:
        print(f"curve {lab}: slope {s:.5g} {a_name}/R per decade of hold")
        print(f"  {'T1/tau':>10}  {'dmu_peak':>12}  {'per decade':>12}  {'case':>5}")
        for j, i in enumerate(idx):
            per = "" if j == 0 else \
                f"{(y[j] - y[j - 1]) / math.log10(x[j] / x[j - 1]):12.5g}" if x[j] > x[j - 1] else ""
            print(f"  {x[j]:>10.4g}  {y[j]:>12.6g}  {per:>12}  {int(i):>5}")
    print(f"dmu_peak = events/mu_max[:, 1] - analytic/mu_pre in units of {a_name}/R "
          f"(/scales/friction); slope: least squares of dmu_peak against log10(T1/tau)")


def main(argv=None):
    ap = map_tool_parser(PROG, __doc__, "mdrmap-map/2 map (.h5) of a slide-hold-slide study",
                         "_healing.png")
    add_select_option(ap, SELECT_HELP + ", e.g. --select v=0.1")
    add_figure_options(ap)
    args, sel, output = parse_map_tool_args(ap, argv)

    import numpy as np

    m, dmu, slip_a, hold, use, notes = read(args, sel, np)
    curves = group_curves(m, use, hold, args.map, np)
    fig, rows = figure(m, curves, dmu, slip_a, hold, args, np)
    for note in notes:
        print(f"{PROG}: {note}")
    report(m, rows)
    save_figure(fig, output, args.dpi)
    print(f"{PROG}: wrote {output}")
    return 0


if __name__ == "__main__":
    sys.exit(run_tool(main, PROG))
