# pyrun-needs: numpy matplotlib h5py mdrmap
"""The master curve of a map over velocity and temperature (or aT): the
stationary friction before t = 0 (results/mu_pre) of every done case against
the reduced velocity aT v, one colour per temperature, over the friction
scale of the map (/scales/friction). Time-temperature superposition
(docs/design.md, "Rheology") says the curves of all temperatures collapse onto
the reference material's curve mu(aT v) at aT = 1.

It checks that claim, independently of the map's own closed forms: for every
done case it asks the Python module for the reference material's stationary
state at aT v (mdrmap.stationary: the same moduli and times, aT = 1) and
prints the largest relative deviation of results/mu_pre (the solver's
stationary state, within the study's rtol) and of analytic/mu_pre (the map's
closed form at the case's temperature, to rounding) from it. The reference
curve is the thin black line.

Usage:
    python3 -m mdrmap map_master_curve master_curve.h5 -o master_curve.png

Exit codes: 0 success, 2 bad input (one line on stderr).
"""

import sys

from ._maplib import (UserError, add_figure_options, add_select_option, fmt,
                    maps, map_tool_parser, open_map2, parse_map_tool_args, read_masked, run_tool,
                    save_figure, select_cases)

PROG = "map_master_curve"
MATERIAL = ("d", "F0", "R", "tau", "G")


def read(path, sel, np):
    """{name: per-case array} of what the tool needs, the done cases --select
    keeps only."""
    f, m = open_map2(path, np, PROG)
    with f:
        for need in ("results/mu_pre", "analytic/mu_pre", "scales/friction", "cases/v"):
            if need not in f:
                raise UserError(f"{path} is an incomplete mdrmap map (no /{need})")
        c = f["cases"]
        n = c["v"].shape[0]
        # under today's names: an old map's prescribed load /cases/FN as F0
        out = {maps.case_name(k): c[k][()] for k in c if c[k].ndim == 1}
        out["aT"] = out.get("aT", np.ones(n))
        out["mu"] = read_masked(f["results/mu_pre"])
        out["mu_an"] = read_masked(f["analytic/mu_pre"])
        out["friction"] = f["scales/friction"][()]
    keep, _ = select_cases(m, sel, np, "--select")
    done = keep & (m["status"] == 1)
    if not done.any():
        raise UserError(f"{path}: no done case selected")
    return {k: v[done] for k, v in out.items()}, int((keep & ~done).sum())


def reference_options(cases, i):
    """mdrmap.stationary's keywords of case i's material at aT = 1 (its spectrum
    as (G, tau) pairs), without the velocity."""
    kw = {k: float(cases[k][i]) for k in MATERIAL  # the loading given (d or F0) only
          if k in cases and (k not in ("d", "F0") or cases[k][i] != 0)}
    terms, k = [], 1
    while f"G{k}" in cases:
        terms.append((float(cases[f"G{k}"][i]), float(cases[f"tau{k}"][i])))
        k += 1
    if terms:
        kw["prony"] = terms
    return kw


def reference_mu(mdrmap, cases, i, v):
    return mdrmap.stationary(**reference_options(cases, i), v=float(v))["mu"]


def check(mdrmap, cases, np):
    """(largest |mu_pre / mu_ref - 1|, the same of analytic/mu_pre)."""
    x = cases["aT"] * cases["v"]
    ref = np.array([reference_mu(mdrmap, cases, i, x[i]) for i in range(x.size)])
    return (float(np.max(np.abs(cases["mu"] / ref - 1))),
            float(np.max(np.abs(cases["mu_an"] / ref - 1))))


def plot(cases, mdrmap, np, args, output):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    x, y = cases["aT"] * cases["v"], cases["mu"] / cases["friction"]
    label = "temperature" if "temperature" in cases else "aT"
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for t in np.unique(cases[label]):
        sel = cases[label] == t
        ax.plot(x[sel], y[sel], "o", ms=4, label=f"{label} {fmt(t)}")
    xs = np.logspace(np.log10(x.min()), np.log10(x.max()), 200)
    ys = [reference_mu(mdrmap, cases, 0, v) / cases["friction"][0] for v in xs]
    ax.plot(xs, ys, "k-", lw=0.8, label="reference (aT = 1)")
    ax.set_xscale("log")
    ax.set_xlabel("reduced velocity aT v")
    ax.set_ylabel("mu / (a/R)")
    ax.set_title(args.title or "master curve: stationary friction against aT v")
    ax.legend(fontsize=7)
    fig.tight_layout()
    save_figure(fig, output, args.dpi)


def main(argv=None):
    ap = map_tool_parser(PROG, __doc__.split("\n\n")[0], "mdrmap-map/2 map over v and "
                         "temperature (or aT)", "_master_curve.png")
    add_select_option(ap)
    add_figure_options(ap)
    args, sel, output = parse_map_tool_args(ap, argv)
    import numpy as np
    import mdrmap

    cases, skipped = read(args.map, sel, np)
    dev, dev_an = check(mdrmap, cases, np)
    print(f"{cases['v'].size} done cases ({skipped} not done): largest |mu_pre / mu_ref(aT v)"
          f" - 1| = {dev:.3g} (the solver), of analytic/mu_pre {dev_an:.3g} (closed form)")
    plot(cases, mdrmap, np, args, output)
    print(f"wrote {output}")
    return 0


if __name__ == "__main__":
    sys.exit(run_tool(main, PROG))
