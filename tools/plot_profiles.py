#!/usr/bin/env python3
# pyrun-needs: numpy matplotlib h5py mdrmap
"""The figure (docs/profiles.md) of stationary friction against velocity for the indenter
profiles on the Kelvin foundation (docs/design.md, "Indenter profiles").

From profile_friction.csv of mdrmap_spectrum_physics (part 7: closed forms and
quadrature of the stationary states, G = tau = 1) it draws mu / g'(a) against
v tau / a at fixed depth (a = a1) and under load (a = a0) for the parabola, the
cone and the power laws n = 1.5 and 3. g'(a) is the slope of the MDR image at
the contact radius (c = (pi/2) tan beta for the cone, 2 a / R for the
parabola, c n a^(n-1) for f = A r^n), the largest slope in contact, so
0 <= mu / g'(a) <= 1; the cone reaches 1 exactly once v tau >= a1. With
--map (the map of jobs/examples/cone_velocity.ini) a third panel shows mu of
the cone study against zeta0 = v tau / a0 for each beta: the stationary start
(results/mu_pre), the state settled after the tenfold step (events/mu_end of
the step, at 10 zeta0), and part 7's curve times (pi/2) tan beta.

    build/tools/physics/mdrmap_spectrum_physics --out OUT --part 7
    mdrmap study --config jobs/examples/cone_velocity.ini --output cone_velocity.h5
    tools/pyrun tools/plot_profiles.py OUT --map cone_velocity.h5 \\
        -o docs/img/profiles_friction_velocity.png --steps docs/img/profiles_cone_steps.png

--steps PNG also draws the map's step responses at one angle (--beta, 10):
mu / c against the slip since each change over a0, one curve per zeta0.

Exit codes: 0 success, 2 bad input (one line on stderr).
"""
import argparse
import csv
import math
import os
import sys

from mdrmap.tools._maplib import UserError, read_masked, run_tool

PROG = "plot_profiles"
# (profile, param) of part 7's CSV -> label, colour, line style
CURVES = [(("parabola", "2"), "parabola (n = 2)", "C0", "-"),
          (("cone", "10"), "cone (n = 1, every beta)", "C3", "-"),
          (("power", "1.5"), "power law n = 1.5", "C2", "--"),
          (("power", "3"), "power law n = 3", "C1", "-.")]
PLATEAU_X = {"depth": 1.0, "load": math.sqrt(2.0 / 3.0)}  # v tau / a where a2 = 0 (cone)


def read_curves(path, np):
    """{(profile, param, loading): (x, mu / g'(a))} of profile_friction.csv."""
    if not os.path.isfile(path):
        raise UserError(f"no such file: {path} (run mdrmap_spectrum_physics --part 7)")
    rows = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            key = (r["profile"], r["param"], r["loading"])
            rows.setdefault(key, []).append((float(r["x"]), float(r["mu_over_slope"])))
    for (profile, param), *_ in CURVES:
        for loading in ("depth", "load"):
            if (profile, param, loading) not in rows:
                raise UserError(f"{path} has no curve {profile} {param} ({loading})")
    return {k: tuple(np.array(v).T) for k, v in rows.items()}


def panel_profiles(ax, curves, loading):
    """mu / g'(a) against v tau / a for the four profiles at one loading."""
    a = "a_1" if loading == "depth" else "a_0"
    for (profile, param), label, col, ls in CURVES:
        x, y = curves[(profile, param, loading)]
        ax.semilogx(x, y, ls, color=col, lw=1.8, label=label)
    if loading == "depth":  # the limits v -> inf: n / (2n - 1)
        for n, text in ((1.5, "3/4"), (2.0, "2/3"), (3.0, "3/5")):
            ax.text(2.5e2, n / (2 * n - 1) + 0.015, text, fontsize=8)
    xp = PLATEAU_X[loading]
    ax.hlines(1.0, xp, 1e3, colors="k", linestyles=":", lw=1.2,
              label="cone: $\\mu = (\\pi/2)\\tan\\beta$ exactly")
    ax.plot([xp], [1.0], "ko", ms=5, mfc="none")
    ax.annotate("cone: the rear face lets go,\n$v\\tau = a_1$" +
                ("" if loading == "depth" else ", $v\\tau/a_0=\\sqrt{2/3}$"),
                (xp, 1.0), xytext=(1.5e-3, 0.82), fontsize=8,
                arrowprops=dict(arrowstyle="->", lw=0.8))
    ax.set_xlim(1e-3, 1e3)
    ax.set_ylim(0, 1.08)
    ax.set_xlabel(f"$v\\,\\tau / {a}$")
    ax.set_ylabel(f"stationary $\\mu\\,/\\,g'({a})$")
    ax.set_title("fixed depth $d$ ($a_1 = (d/c)^{1/n}$)" if loading == "depth" else
                 "under load $F_0$ ($a_0$: the elastic contact radius)", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)


def read_map(path):
    """(beta, zeta0, mu_pre, mu_end of the first change, w1/v, c = g'(a0) = twice
    /scales/friction) of the done cases. Read with h5py: the package's opener
    (maps.open_h5) still requires the parabola's /cases/R and refuses a cone's map."""
    import h5py

    if not os.path.isfile(path):
        raise UserError(f"no such file: {path}")
    with h5py.File(path, "r") as f:
        if "cases/beta" not in f or "scales/length" not in f or "events/mu_end" not in f:
            raise UserError(f"{path} is not an mdrmap-map/2 map of a cone study")
        c = {k: f[f"cases/{k}"][()] for k in ("beta", "v")}
        w1 = f["cases/w"][()][:, 0]
        zeta = c["v"] * f["scales/time"][()] / f["scales/length"][()]
        mu, mu_end = read_masked(f["results/mu_pre"]), read_masked(f["events/mu_end"])[:, 0]
        slope = 2.0 * f["scales/friction"][()]
        done = f["results/status"][()] == 1
    return tuple(x[done] for x in (c["beta"], zeta, mu, mu_end, w1 / c["v"], slope))


def panel_map(ax, curves, path):
    """mu of the cone study against zeta0, one colour per beta."""
    beta, z, mu, mu_end, ratio, slope = read_map(path)
    x, y = curves[("cone", "10", "load")]
    for i, b in enumerate(sorted(set(beta))):
        col, k = f"C{i}", beta == b
        c = slope[k][0]
        ax.loglog(x, c * y, "-", color=col, lw=1, alpha=0.7)
        ax.loglog(z[k], mu[k], "o", color=col, mfc="none", ms=6,
                  label=f"$\\beta = {b:g}°$: $(\\pi/2)\\tan\\beta = {c:.4f}$")
        ax.loglog(z[k] * ratio[k], mu_end[k], "x", color=col, ms=6)
    ax.plot([], [], "ko", mfc="none", label="results/mu_pre (stationary start)")
    ax.plot([], [], "kx", label="events/mu_end after $v \\to 10v$ (at $10\\zeta_0$)")
    ax.plot([], [], "k-", lw=1, label="part 7 $\\times (\\pi/2)\\tan\\beta$")
    ax.axvline(PLATEAU_X["load"], color="k", ls=":", lw=1)
    ax.text(PLATEAU_X["load"] * 1.1, 1.25, "$v\\tau = a_1$: $\\zeta_0 = \\sqrt{2/3}$", fontsize=8)
    ax.set_xlim(3e-3, 1e2)
    ax.set_ylim(1e-3, 2)
    ax.set_xlabel("$\\zeta_0 = v\\,\\tau / a_0$")
    ax.set_ylabel("stationary $\\mu$")
    ax.set_title(f"cone under load: the study {os.path.basename(path)}", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7.5, loc="lower right")


def read_steps(path, beta, np):
    """[(zeta0, [(slip / a0, mu / c) of each segment])] of the done cases at beta."""
    import h5py

    with h5py.File(path, "r") as f:
        if "timeseries/mu" not in f:
            raise UserError(f"{path} has no time series (timeseries = true)")
        k = np.flatnonzero((f["cases/beta"][()] == beta) & (f["results/status"][()] == 1))
        if k.size == 0:
            raise UserError(f"{path}: no done case with beta = {beta:g}")
        t, mu, seg = f["timeseries/t"][()], f["timeseries/mu"][()], f["timeseries/segment"][()]
        w, T, v = f["cases/w"][()], f["cases/T"][()], f["cases/v"][()]
        a0, tau, fr = (f[f"scales/{s}"][()] for s in ("length", "time", "friction"))
    out = []
    for i in k:
        t0 = np.concatenate([[0.0], np.cumsum(T[i])])
        segs = [((t[i, seg == j] - t0[j]) * w[i, j] / a0[i], mu[i, seg == j] / (2 * fr[i]))
                for j in range(w.shape[1])]
        out.append((v[i] * tau[i] / a0[i], segs))
    return out


def steps_figure(path, beta, output, plt, np):
    """mu / c against the slip since each change, one curve per zeta0."""
    cases = read_steps(path, beta, np)
    fig, axes = plt.subplots(1, len(cases[0][1]), figsize=(11, 4.2), sharey=True)
    cmap = plt.get_cmap("viridis")
    for n, (z, segs) in enumerate(cases):
        col = cmap(n / max(len(cases) - 1, 1))
        for ax, (s, m) in zip(axes, segs):
            ok = s > 0
            ax.semilogx(s[ok], m[ok], "-", color=col, label=f"$\\zeta_0 = {z:.3g}$")
            ax.plot([1e-6], [m[0]], "<", color=col, ms=6, clip_on=False)  # mu(0+)
    for j, ax in enumerate(axes):
        ax.set_xlim(1e-6, 10)
        ax.set_xlabel("slip since the change / $a_0$")
        ax.set_title(f"change {j + 1}: $w_{j + 1}/v$ = {'10' if j == 0 else '1'}", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("$\\mu\\,/\\,((\\pi/2)\\tan\\beta)$")
    axes[-1].legend(fontsize=8)
    fig.suptitle(f"cone under load, $\\beta = {beta:g}°$: $v \\to 10v \\to v$ "
                 f"({os.path.basename(path)}); triangles: $\\mu$ just after the change",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(output, dpi=130)
    print(f"{PROG}: wrote {output}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("csv_dir", help="--out DIR of mdrmap_spectrum_physics (profile_friction.csv)")
    ap.add_argument("--map", help="the map of jobs/examples/cone_velocity.ini: a third panel")
    ap.add_argument("-o", "--output", default="profiles_friction_velocity.png")
    ap.add_argument("--steps", metavar="PNG", help="with --map: also the step responses")
    ap.add_argument("--beta", type=float, default=10.0, help="--steps: the cone angle (10)")
    args = ap.parse_args(argv)

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    curves = read_curves(os.path.join(args.csv_dir, "profile_friction.csv"), np)
    n = 3 if args.map else 2
    fig, axes = plt.subplots(1, n, figsize=(5.2 * n, 4.6))
    for ax, loading in zip(axes, ("depth", "load")):
        panel_profiles(ax, curves, loading)
    axes[1].legend(fontsize=7.5, loc="center right", bbox_to_anchor=(1.0, 0.62))
    if args.map:
        panel_map(axes[2], curves, args.map)
    fig.suptitle("Stationary friction on the Kelvin foundation. $g'(a)$: the slope of the MDR "
                 "image at the contact radius, the upper bound of $\\mu$\n($c = (\\pi/2)\\tan"
                 "\\beta$ for the cone, $2a/R$ for the parabola, $c\\,n\\,a^{n-1}$ for "
                 "$f = A r^n$)", fontsize=9.5)
    fig.tight_layout()
    fig.savefig(args.output, dpi=130)
    print(f"{PROG}: wrote {args.output}")
    if args.steps and args.map:
        steps_figure(args.map, args.beta, args.steps, plt, np)
    return 0


if __name__ == "__main__":
    sys.exit(run_tool(main, PROG))
