#!/usr/bin/env python3
"""The figures of relaxation-spectrum physics (docs/physics.md), from the CSV files of
mdrmap_spectrum_physics (tools/physics/spectrum_physics.cpp).

    build/tools/physics/mdrmap_spectrum_physics --out OUT
    /usr/bin/python3 tools/plot_spectrum_physics.py OUT [--fig-dir docs/img]

Writes spectrum_sls_load.png, spectrum_width.png, spectrum_healing.png,
spectrum_direct.png, spectrum_creep.png and spectrum_healing_load.png (each
only where its CSV exists).
"""
import argparse
import csv
import os
import sys
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_groups(path, ncols_key):
    """Rows of a CSV grouped by their first ncols_key columns (in order)."""
    groups = OrderedDict()
    with open(path) as f:
        rows = csv.reader(f)
        header = next(rows)
        for row in rows:
            key = tuple(row[:ncols_key])
            groups.setdefault(key, []).append([float(x) for x in row[ncols_key:]])
    return header, OrderedDict((k, np.array(v)) for k, v in groups.items())


def fig_sls(src, out):
    _, g = read_groups(src, 2)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for (model, ratio), a in g.items():
        v, mu = a[:, 0], a[:, 1]
        if model == "kelvin":
            ax2.plot(v, mu, "k--", lw=2, label="Kelvin ($v\\,\\tau_K/a_0$)")
            continue
        r = float(ratio)
        lab = "$G_0/G$ = %g" % r
        ax1.semilogx(v, mu, label=lab)
        ax2.semilogx(v * (r - 1.0), mu, label=lab)
        i = np.argmax(mu)
        ax1.plot(v[i], mu[i], "k.", ms=5)
    ax1.set_xlabel("$v\\,\\tau_1/a_0$")
    ax2.set_xlabel("$v\\,\\tau_K/a_0$, $\\tau_K = \\tau_1 G_1/G$")
    for ax in (ax1, ax2):
        ax.set_ylabel("$\\mu\\,/\\,(a_0/R)$")
        ax.grid(alpha=0.3)
    ax1.set_xlim(1e-6, 1e2)
    ax2.set_xlim(1e-3, 1e3)
    ax2.legend(fontsize=8)
    ax1.set_title("standard linear solid under load: stationary friction")
    ax2.set_title("in the Kelvin time: the bell is approached as $G_0/G\\to\\infty$")
    fig.tight_layout()
    fig.savefig(out, dpi=130)


def fig_width(src, out):
    _, g = read_groups(src, 3)
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2))
    for (spec, ratio, loading), a in g.items():
        v, mu = a[:, 0], a[:, 1]
        if spec == "PIB":
            axes[2].loglog(v, mu, label="PIB, " + ("fixed depth" if loading == "depth"
                                                   else "under load"))
            continue
        if float(ratio) != 1000.0:
            continue
        ax = axes[0] if loading == "depth" else axes[1]
        lab = ("%s terms, 1/decade" % spec[1:]) if "p" not in spec else \
            "6 terms, $G_k\\propto\\tau_k^{%s}$" % spec.split("p")[1]
        ax.semilogx(v, mu / mu.max(), label=lab)
    for ax, t in zip(axes[:2], ("fixed depth", "under load")):
        ax.axhline(0.5, color="gray", lw=0.8)
        ax.set_xlim(1e-6, 1e5)
        ax.set_xlabel("$v\\,\\tau_{max}/a$  ($a = a_1$ or $a_0$)")
        ax.set_ylabel("$\\mu/\\mu^*$")
        ax.set_title("$G_0/G = 10^3$, tau = 0, %s" % t)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    axes[2].set_xlabel("$v/a$ [1/s]")
    axes[2].set_ylabel("$\\mu/(a/R)$")
    axes[2].set_title("polyisobutylene, 30 terms, G = 1e5 Pa")
    axes[2].grid(alpha=0.3)
    axes[2].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=130)


def relaxed_fraction(p, ratio, t):
    """G(t)/G0 of the spectra of part 3: G = 1, tau_k = 1e-5..1, sum G_k = G0/G - 1,
    G_k ~ tau_k^p (decade_spectrum in spectrum_physics.cpp) or, for p == "sqrt",
    sqrt(G(t)/G0) falling by equal steps (sqrt_linear_spectrum)."""
    taus = 10.0 ** np.arange(-5, 1)
    if p == "sqrt":
        s = (1.0 - np.sqrt(1.0 / ratio)) / 6.0
        k = np.arange(6)
        w = ratio * ((1.0 - s * k) ** 2 - (1.0 - s * (k + 1)) ** 2)
    else:
        w = taus ** float(p)
        w *= (ratio - 1.0) / w.sum()
    return np.array([(1.0 + np.sum(w * np.exp(-x / taus))) / ratio for x in t])


def fig_healing(src, out):
    _, g = read_groups(src, 4)
    fig, axes = plt.subplots(2, 2, figsize=(12, 8.5))
    axes = axes.ravel()
    for (spec, p, ratio, zeta), a in g.items():
        th, heal = a[:, 0], a[:, 3]
        lab = "%s, $G_0/G$=%s, $v_0\\tau_6/a_1$=%s" % (
            "$\\sqrt{G(t)}$ linear in log t" if p == "sqrt" else "$G_k\\propto\\tau_k^{%s}$" % p,
            ratio, zeta)
        axes[0].semilogx(th, heal, ".-", label=lab)
        x = np.log10(th)
        axes[1].semilogx(np.sqrt(th[1:] * th[:-1]), np.diff(heal) / np.diff(x), ".-", label=lab)
        if p == "0" and ratio == "100" and zeta == "1e+06":
            fx, fn_peak, fn_hold = a[:, 5], a[:, 6], a[:, 7]
            axes[2].semilogx(th, fx / fx[0], label="$F_x$ at the peak")
            axes[2].semilogx(th, fn_peak / fn_peak[0], label="$F_N$ at the peak")
            axes[2].semilogx(th, fn_hold / fn_hold[0], label="$F_N$ at the end of the hold")
            axes[2].semilogx(th, a[:, 2] / a[0, 2], label="$\\mu$ at the peak")
            axes[2].semilogx(th, relaxed_fraction("0", 100.0, th), "k:",
                             label="$G(t_{hold})/G_0$")
        axes[3].semilogx(relaxed_fraction(p, float(ratio), th), a[:, 2], ".",
                         label=lab)
    for ax in axes[:3]:
        ax.axvspan(1e-5, 1.0, color="0.92", zorder=0)
        ax.set_xlabel("hold time / longest $\\tau_k$")
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("healing $\\mu_{peak}-\\mu_{ss}$  [$a_1/R$]")
    axes[1].set_ylabel("$\\beta$ = d healing / d log$_{10}$ hold  [$a_1/R$]")
    axes[2].set_ylabel("relative to the shortest hold")
    axes[2].set_yscale("log")
    axes[3].set_xscale("log")
    axes[3].set_xlabel("relaxed modulus at the end of the hold, $G(t_{hold})/G_0$")
    axes[3].set_ylabel("$\\mu$ at the peak  [$a_1/R$]")
    axes[0].legend(fontsize=6)
    axes[2].legend(fontsize=7)
    axes[0].set_title("slide-hold-slide at fixed depth, 6 terms $\\tau_k = 10^{-5..0}$")
    axes[1].set_title("healing per decade of hold (grey: span of the spectrum)")
    axes[2].set_title("p = 0, $G_0/G$ = 100: what the peak is made of")
    axes[3].set_title("$\\mu_{peak}$ against the relaxed modulus: one curve")
    fig.tight_layout()
    fig.savefig(out, dpi=120)


def fig_healing_load(src, out):
    """Study 6: healing under load against fixed depth, beta per decade, the
    contact's creep during the hold against Lee-Radok; runs left out (status
    other than "done") are not drawn."""
    runs = OrderedDict()
    with open(src) as f:
        for row in csv.DictReader(f):
            if row["status"] != "done":
                continue
            runs.setdefault(row["spectrum"], {}).setdefault(row["loading"], []).append(
                [float(row[k]) for k in ("t_hold", "healing", "a1_hold", "a1_creep",
                                         "mu_peak")])
    names = {"SLS": "SLS, $\\tau_1$ = 1", "6x-equal": "6 terms, equal weights",
             "6x-sqrt": "6 terms, $\\sqrt{G(t)}$ linear in log t"}
    fig, axes = plt.subplots(2, 2, figsize=(12, 8.5))
    axes = axes.ravel()
    for n, (spec, by) in enumerate(runs.items()):
        color = "C%d" % n
        lab = names.get(spec.split(",")[0], spec)
        for loading, style in (("depth", "--"), ("load", "-")):
            if loading not in by:
                continue
            a = np.array(by[loading])
            th, heal = a[:, 0], a[:, 1]
            where = "fixed depth" if loading == "depth" else "under load"
            axes[0].semilogx(th, heal, style, marker=".", color=color,
                             label="%s, %s" % (lab, where))
            x = np.log10(th)
            axes[1].semilogx(np.sqrt(th[1:] * th[:-1]), np.diff(heal) / np.diff(x), style,
                             marker=".", color=color)
            if loading == "load":
                axes[2].semilogx(th, a[:, 2], ".", color=color, label=lab + ": solver")
                axes[2].semilogx(th, a[:, 3], "-", color=color, lw=0.8,
                                 label=lab + ": Lee-Radok")
                axes[3].semilogx(th, a[:, 4] / a[:, 2], "-", marker=".", color=color,
                                 label=lab + ", under load: $\\mu_{peak}/(a_{1,hold}/R)$")
            else:
                axes[3].semilogx(th, a[:, 4], "--", marker=".", color=color,
                                 label=lab + ", fixed depth: $\\mu_{peak}/(a_1/R)$")
    for ax in axes:
        ax.axvspan(1e-5, 1.0, color="0.92", zorder=0)
        ax.set_xlim(5e-4, 2e4)
        ax.set_xlabel("hold time / longest $\\tau_k$ (grey: the six-term spectra's span)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("healing $\\mu_{peak}-\\mu_{ss}$  [$a_1/R$]")
    axes[1].set_ylabel("$\\beta$ = d healing / d log$_{10}$ hold  [$a_1/R$]")
    axes[2].set_ylabel("contact half-width at the end of the hold  [$a_1$]")
    axes[3].set_ylabel("$\\mu_{peak}$ in units of the contact at the end of the hold")
    axes[0].legend(fontsize=7)
    axes[2].legend(fontsize=7)
    axes[3].legend(fontsize=6)
    axes[0].set_title("slide-hold-slide, $G_0/G$ = 100 (dashed: fixed depth, solid: load)")
    axes[1].set_title("healing per decade of hold (dashed: fixed depth, solid: load)")
    axes[2].set_title("under load the contact creeps: Lee-Radok")
    axes[3].set_title("the peak per contact size")
    fig.tight_layout()
    fig.savefig(out, dpi=120)


def fig_direct(src, out):
    _, g = read_groups(src, 1)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for (spec,), a in g.items():
        t, dmu = a[:, 0], a[:, 2]
        ok = t > 0
        ax = axes[0] if spec.startswith("SLS") else axes[1]
        ax.semilogx(t[ok], dmu[ok], label=spec.split()[-1].replace("z=", "$v\\tau_{min}/a_1$ = "))
    for ax, title in zip(axes, ("standard linear solid, $G_0/G$ = 10",
                                "6 terms a decade apart, $G_0/G$ = 100")):
        ax.axhline(0.0, color="gray", lw=0.8)
        ax.set_xlabel("time since the step $v \\to 10v$ / shortest $\\tau_k$")
        ax.set_ylabel("$\\mu - \\mu_{before}$  [$a_1/R$]")
        ax.set_title(title + ": no jump at the step")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        ax.set_xlim(1e-5, 1e2)
    fig.tight_layout()
    fig.savefig(out, dpi=130)


def fig_creep(src, out):
    _, g = read_groups(src, 1)
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for (spec,), a in g.items():
        t = a[:, 0]
        line, = ax.semilogx(t, a[:, 1], label=spec + ": creep_depth (J(t))")
        ax.semilogx(t[::4], a[::4, 2], "x", color=line.get_color(), ms=5)
        ax.semilogx(t[2::4], a[2::4, 3], "o", mfc="none", color=line.get_color(), ms=4)
    ax.plot([], [], "kx", label="Talbot inversion of $\\bar J(s)$")
    ax.plot([], [], "ko", mfc="none", label="hereditary integral (Lee-Radok)")
    ax.set_xlabel("time since the step load")
    ax.set_ylabel("depth $d/d_0$")
    ax.set_yscale("log")
    ax.set_title("creep from rest under a step load")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out, dpi=130)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("csv_dir", help="the --out DIR of mdrmap_spectrum_physics")
    ap.add_argument("--fig-dir", default="docs/img", help="where the PNGs go")
    args = ap.parse_args()
    if not os.path.isdir(args.csv_dir):
        print("plot_spectrum_physics.py: csv_dir %s is not a directory" % args.csv_dir,
              file=sys.stderr)
        return 2
    os.makedirs(args.fig_dir, exist_ok=True)
    figures = [("spectrum_sls_load", fig_sls), ("spectrum_width", fig_width),
               ("spectrum_healing", fig_healing), ("spectrum_direct", fig_direct),
               ("spectrum_creep", fig_creep), ("spectrum_healing_load", fig_healing_load)]
    for name, make in figures:
        src = os.path.join(args.csv_dir, name + ".csv")
        if os.path.exists(src):
            out = os.path.join(args.fig_dir, name + ".png")
            make(src, out)
            print("wrote", out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
