#!/usr/bin/env python3
# pyrun-needs: numpy matplotlib h5py
"""Plot the response to a velocity step from an mdrmap map (the seed paper's Figure 2).

Four panels against time, for one or more cases of a map written with
`timeseries = true` (or `--timeseries true`):

  (a) normal force F_N   (b) friction force F_x   (c) friction coefficient mu
  (d) trailing edge a2 / a1,  a1 = sqrt(R d)

Time is t / tau (t when a plotted case has tau = 0), measured from the step.
Besides the simulated curve of each case (from /timeseries) the panels show:

  - the stationary level before the step (results/*_pre), as a short segment
    at t < 0, joined to the value at t = 0+ by a thin dotted jump;
  - the analytic value just after the step (analytic/*_jump, eqs. 15/16), as
    an open circle at t = 0;
  - the stationary level at v1 (analytic/*_post), dashed;
  - for mu, the limits (4/3) sqrt(d/R) for v -> inf (analytic/mu_inf) and
    (3/4) sqrt(d/R) right after a stop (analytic/mu_post_drop), dotted;
  - for a2, when a case has v1/v <= 1e-3, the start-stop limit
    a2 = a1 sqrt(1 - exp(-t/tau)) (it holds for v tau >> a1 and v1 tau << a1).

`--zoom` scales the force axes to t >= 0 only (the forces can drop by orders of
magnitude at the step); the level before the step is then written as an
arrow with its value when it is off the axis.

Cases: `--case I` (repeatable, 0-based row of the map, or `all` for every done
case), `--select d=1e-3,v1_over_v=1e-4` (repeatable; the done case nearest in
those parameters: d R tau v v1 G v1_over_v zeta zeta1, log distance for
positive values), default the first done case. Cases that are pending or
failed are skipped, and the tool says how many.

`--scaled` divides by the natural scales of the similarity law: F_N / (G a1 d),
F_x / (G d^2), mu / sqrt(d/R); cases with the same zeta = v tau / a1 and
zeta1 = v1 tau / a1 then fall on the same curves.

mdrmap-map/2 maps (a history of K segments, docs/map-schema.md) are read too:
the time series run over all segments ([N, K*S]; t from the first change at
t = 0), the dashed level is the stationary state of the last segment
(analytic/<q>_ss), the a2 panel is a2 / a with a = a1 = sqrt(R d) at depth or
a0 = (3 FN R / (16 G))^(1/3) under load, `--scaled` divides forces by
G a^3 / R and mu by a/R, and `--select` names the parameters d or FN, R, tau,
G, v, w1, T1, ... and zeta = v tau / a, zeta1 = w1 tau / a.

Usage:
    tools/pyrun tools/plot_timeseries.py MAP.h5 -o figure2.png
    tools/pyrun tools/plot_timeseries.py MAP.h5 --case all --scaled -o figure2.png
    tools/pyrun tools/plot_timeseries.py MAP.h5 --select d=1e-3,v=10 -o case.png

Exit codes: 0 success, 2 bad input (one line on stderr).
"""

import argparse
import math
import os
import sys

from maplib import (CASE_COLS, Parser, UserError, case_columns, failure_messages, load_cases,
                    open_map, read_masked, run_tool, save_figure, schema_version)

PROG = "plot_timeseries"
QUANT = ["FN", "Fx", "mu", "a2"]
DERIVED = ["v1_over_v", "zeta", "zeta1"]
MAX_LISTED = 8  # skipped cases listed by number at most


def fmt(x):
    """Compact number: 1e-04 -> 1e-4, 10000 -> 1e4, 0.5 -> 0.5."""
    if x == 0:
        return "0"
    s = f"{x:.3g}"
    if "e" in s:
        mant, exp = s.split("e")
        return f"{mant}e{int(exp)}"
    if abs(x) >= 1e4:
        e = int(math.floor(math.log10(abs(x))))
        mant = x / 10**e
        m = f"{mant:.3g}"
        return f"{m}e{e}" if m != "1" else f"1e{e}"
    return s


def load2(f, path, np):
    """An mdrmap-map/2 map in the form the plot reads."""
    c = load_cases(f, path, np)
    n, K = c["n"], c["K"]
    m = {"path": path, "version": 2, "n": n, "status": c["status"], "message": c["message"],
         "a": c["a"], "mu_scale": c["mu_scale"], "loading": c["loading"], "K": K}
    m.update(c["cols"])
    seg = [f"{kind}{j + 1}" for j in range(K) for kind in ("w", "T")]
    for j in range(K):
        m[f"w{j + 1}"], m[f"T{j + 1}"] = c["w"][:, j], c["T"][:, j]
        with np.errstate(divide="ignore", invalid="ignore"):
            m[f"w{j + 1}_over_v"] = c["w"][:, j] / c["cols"]["v"]
            m[f"T{j + 1}_over_tau"] = c["T"][:, j] / c["cols"]["tau"]
    m["case_cols"] = list(c["cols"]) + seg
    m["v1"] = c["w"][:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        m["a1"] = c["a"]
        m["v1_over_v"] = m["v1"] / m["v"]
        m["zeta"] = c["zeta"]
        m["zeta1"] = m["v1"] * m["tau"] / c["a"]
    m["derived"] = ["zeta", "zeta1"] + [f"{kind}{j + 1}_over_{ref}" for j in range(K)
                                        for kind, ref in (("w", "v"), ("T", "tau"))] + \
        ["v1", "v1_over_v"]  # the seed's names of w1, w1_over_v
    for q in QUANT:
        for grp, name in [("results", f"{q}_pre"), ("analytic", f"{q}_jump")]:
            if f"{grp}/{name}" in f and f[f"{grp}/{name}"].shape == (n,):
                m[f"{grp}/{name}"] = read_masked(f[f"{grp}/{name}"])
        if f"analytic/{q}_ss" in f:  # the stationary level of the last segment
            m[f"analytic/{q}_post"] = read_masked(f[f"analytic/{q}_ss"]).reshape(n, K)[:, -1]
    m["ts"] = {s: np.asarray(f[f"timeseries/{s}"][()], dtype=float) for s in ["t"] + QUANT}
    return m


def load(path, np, h5py):
    f = open_map(path, h5py, PROG)
    if schema_version(f) == 2:
        with f:
            if "timeseries" not in f or any(f"timeseries/{s}" not in f for s in ["t"] + QUANT):
                raise UserError(f"{path} has no /timeseries; rerun the study with "
                                f"`--timeseries true` (or timeseries = true in [run])")
            return load2(f, path, np)
    with f:
        if "timeseries" not in f or any(f"timeseries/{s}" not in f for s in ["t"] + QUANT):
            raise UserError(f"{path} has no /timeseries; rerun the study with "
                            f"`--timeseries true` (or timeseries = true in [run])")
        m = {"path": path}
        n = f["results/status"].shape[0]
        m["n"] = n
        m["status"] = f["results/status"][()].astype(int)
        m["message"] = failure_messages(f, n)
        m["version"], m["derived"] = 1, DERIVED
        # the /cases columns: from /schema (older maps: CASE_COLS), with those
        # the derived variables need
        m["case_cols"] = case_columns(f)
        for c in m["case_cols"] + [c for c in CASE_COLS if c not in m["case_cols"]]:
            m[c] = f[f"cases/{c}"][()] if f"cases/{c}" in f else np.ones(n)
        for grp in ["results", "analytic"]:
            for name in f[grp] if grp in f else []:
                ds = f[f"{grp}/{name}"]
                if ds.dtype.kind == "f" and ds.shape == (n,):
                    m[f"{grp}/{name}"] = ds[()]
        m["ts"] = {s: f[f"timeseries/{s}"][()] for s in ["t"] + QUANT}
    with np.errstate(divide="ignore", invalid="ignore"):
        m["a1"] = np.sqrt(m["R"] * m["d"])
        m["v1_over_v"] = m["v1"] / m["v"]
        m["zeta"] = m["v"] * m["tau"] / m["a1"]
        m["zeta1"] = m["v1"] * m["tau"] / m["a1"]
    return m


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
    if m["version"] == 2:
        s = ", ".join(f"{tau if c == 'tau' else c}={fmt(m[c][i])}" for c in m["case_cols"]
                      if c != "G" or m["G"][i] != 1)
        if m["tau"][i] > 0:
            s += f"  ({zeta}={fmt(m['zeta'][i])}, {zeta1}={fmt(m['zeta1'][i])})"
        return s
    s = (f"d={fmt(m['d'][i])}, R={fmt(m['R'][i])}, {tau}={fmt(m['tau'][i])}, "
         f"v={fmt(m['v'][i])}, v1={fmt(m['v1'][i])}")
    if m["G"][i] != 1:
        s += f", G={fmt(m['G'][i])}"
    if m["tau"][i] > 0:
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


def main(argv=None):
    ap = Parser(prog=PROG, description=__doc__,
                formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("map", help="mdrmap map (.h5) written with timeseries = true")
    ap.add_argument("-o", "--output", default=None,
                    help="PNG to write (default: <map name>_timeseries.png in the current directory)")
    ap.add_argument("--case", action="append", metavar="I",
                    help="case number (0-based row of the map), repeatable; 'all' for every done case")
    ap.add_argument("--select", action="append", metavar="SPEC",
                    help="the done case nearest to SPEC, e.g. d=1e-3,v1_over_v=1e-4 "
                         "(names: d R tau v v1 G v1_over_v zeta zeta1); repeatable")
    ap.add_argument("--scaled", action="store_true",
                    help="plot F_N/(G a1 d), F_x/(G d^2), mu/sqrt(d/R) (similarity scales)")
    ap.add_argument("--ylog", choices=["auto", "on", "off"], default="auto",
                    help="log y axis for F_N, F_x, mu: auto = when the values span more "
                         "than two decades (default auto)")
    ap.add_argument("--start-stop", choices=["auto", "on", "off"], default="auto",
                    help="draw a1 sqrt(1-exp(-t/tau)) in the a2 panel: auto = when a case "
                         "has v1/v <= 1e-3 (default auto)")
    ap.add_argument("--zoom", action="store_true",
                    help="scale the F_N and F_x axes to t >= 0; a level before the step above "
                         "the range is written as an arrow with its value")
    ap.add_argument("--t-max", type=float, default=None, metavar="T",
                    help="right end of the time axis (in t/tau, or t when tau = 0)")
    ap.add_argument("--title", default=None, help="figure title")
    ap.add_argument("--dpi", type=int, default=120, help="resolution (default 120)")
    args = ap.parse_args(argv)
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

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    ts = m["ts"]
    use_tau = all(m["tau"][i] > 0 for i in cases)
    xs = {i: ts["t"][i] / m["tau"][i] if use_tau else ts["t"][i] for i in cases}
    xmax = args.t_max or max(float(np.nanmax(xs[i])) for i in cases)
    if not xmax > 0:
        xmax = 1.0
    pre_len = 0.08 * xmax

    def scale(q, i):
        if m["version"] == 2:
            a, G, R = m["a"][i], m["G"][i], m["R"][i]
            if q == "a2":
                return a
            if not args.scaled:
                return 1.0
            return {"FN": G * a ** 3 / R, "Fx": G * a ** 3 / R, "mu": a / R}[q]
        G, d, R, a1 = m["G"][i], m["d"][i], m["R"][i], m["a1"][i]
        if q == "a2":
            return a1
        if not args.scaled:
            return 1.0
        return {"FN": G * a1 * d, "Fx": G * d * d, "mu": math.sqrt(d / R)}[q]

    labels = {
        "FN": ("(a) normal force", "F$_N$ / (G a$_1$ d)" if args.scaled else "F$_N$  [G length$^2$]"),
        "Fx": ("(b) friction force", "F$_x$ / (G d$^2$)" if args.scaled else "F$_x$  [G length$^2$]"),
        "mu": ("(c) friction coefficient",
               "\u03bc / \u221a(d/R)" if args.scaled else "\u03bc = F$_x$ / F$_N$"),
        "a2": ("(d) trailing edge", "a$_2$ / a$_1$"),
    }
    if m["version"] == 2:
        a = "a$_0$" if m["loading"] == "force" else "a$_1$"
        labels["FN"] = ("(a) normal force", f"F$_N$ / (G {a}$^3$/R)" if args.scaled else
                        "F$_N$  [G length$^2$]")
        labels["Fx"] = ("(b) friction force", f"F$_x$ / (G {a}$^3$/R)" if args.scaled else
                        "F$_x$  [G length$^2$]")
        labels["mu"] = ("(c) friction coefficient", f"\u03bc / ({a}/R)" if args.scaled else
                        "\u03bc = F$_x$ / F$_N$")
        labels["a2"] = ("(d) trailing edge", f"a$_2$ / {a}")
    if len(cases) <= 10:
        colours = [plt.get_cmap("tab10")(k) for k in range(len(cases))]
    else:
        colours = [plt.get_cmap("viridis")(k / (len(cases) - 1)) for k in range(len(cases))]

    fig, axes = plt.subplots(2, 2, figsize=(12, 8.4), sharex=True)
    axes = axes.ravel()
    for ax, q in zip(axes, QUANT):
        values = []
        pre_levels = []  # (colour, level) left out of the y range with --zoom
        zoom = args.zoom and q in ("FN", "Fx")
        for c, i in zip(colours, cases):
            s = scale(q, i)
            y = ts[q][i] / s
            x = xs[i]
            keep = x <= xmax * (1 + 1e-12)
            ax.plot(x[keep], y[keep], color=c, lw=1.6, zorder=3)
            values.append(y[keep])
            pre = m.get(f"results/{q}_pre")
            if pre is not None:
                yp = pre[i] / s
                ax.plot([-pre_len, 0], [yp, yp], color=c, lw=1.6, zorder=3)
                ax.plot([0, 0], [yp, y[0]], color=c, lw=0.8, ls=":", zorder=2)
                if zoom:
                    pre_levels.append((c, yp))
                else:
                    values.append(np.array([yp]))
            jump = m.get(f"analytic/{q}_jump")
            if jump is not None:
                ax.plot([0], [jump[i] / s], marker="o", ms=8, mfc="none", mec=c, mew=1.4,
                        ls="none", zorder=4)
                values.append(np.array([jump[i] / s]))
            post = m.get(f"analytic/{q}_post")
            if post is not None:
                ax.plot([0, xmax], [post[i] / s] * 2, color=c, lw=1.0, ls="--", alpha=0.75, zorder=2)
                values.append(np.array([post[i] / s]))
        if q == "mu":
            drawn = []
            for c, i in zip(colours, cases):
                s = scale(q, i)
                for key, tag in [("analytic/mu_inf", "4/3"), ("analytic/mu_post_drop", "3/4")]:
                    if key not in m:
                        continue
                    val = m[key][i] / s
                    if any(abs(val - v0) <= 1e-9 * abs(val) for v0 in drawn):
                        continue
                    drawn.append(val)
                    col = "black" if args.scaled or len(cases) == 1 else c
                    ax.axhline(val, color=col, lw=1.0, ls=":", zorder=1)
                    values.append(np.array([val]))
                    if args.scaled or len(cases) == 1:
                        ax.annotate(f"{tag} \u221a(d/R)", (1.0, val), xycoords=("axes fraction", "data"),
                                    xytext=(-4, 3), textcoords="offset points", ha="right",
                                    va="bottom", fontsize=8)
        if q == "a2":
            ref = [i for i in cases if m["tau"][i] > 0 and (
                args.start_stop == "on" or
                (args.start_stop == "auto" and m["v1_over_v"][i] <= 1e-3
                 and m.get("K", 1) == 1))]
            taus = sorted({1.0 if use_tau else float(m["tau"][i]) for i in ref})
            for tau_ref in taus:  # one curve on a t/tau axis, else one per tau
                xr = np.linspace(0, xmax, 400)
                ax.plot(xr, np.sqrt(1 - np.exp(-xr / tau_ref)), color="black", lw=1.2, ls="-.",
                        zorder=5)
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
        else:
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
                out = [(c, yp) for c, yp in pre_levels if yp > top]
                for k, (c, yp) in enumerate(out):
                    ax.annotate(f"\u2191{fmt(yp)}", xy=(-1.5 * pre_len, top), xycoords="data",
                                xytext=(2, -9 - 10 * k), textcoords="offset points", ha="left",
                                va="center", fontsize=7, color=c)
            if log:
                ax.set_yscale("log")
                if pos.size < allv.size:
                    ax.text(0.98, 0.5, "values = 0 are not shown on the log axis",
                            transform=ax.transAxes, fontsize=7.5, color="0.3", ha="right")
        title, ylabel = labels[q]
        ax.set_title(title, fontsize=11, loc="left")
        ax.set_ylabel(ylabel)
        ax.axvline(0, color="0.6", lw=0.6, zorder=0)
        ax.grid(True, alpha=0.25)
        ax.set_xlim(-1.5 * pre_len, xmax)
    for ax in axes[2:]:
        ax.set_xlabel("t / \u03c4" if use_tau else "t  (a plotted case has \u03c4 = 0)")

    case_handles = [Line2D([], [], color=c, lw=2) for c in colours]
    case_labels = [f"case {i}: {case_params(m, i)}" for i in cases]
    grey = "0.35"
    style_handles = [
        Line2D([], [], color=grey, lw=1.6),
        Line2D([], [], color=grey, marker="o", mfc="none", ls="none", ms=8),
        Line2D([], [], color=grey, lw=1.0, ls="--"),
        Line2D([], [], color="black", lw=1.0, ls=":"),
        Line2D([], [], color="black", lw=1.2, ls="-."),
    ]
    style_labels = [
        "mdrmap (t < 0: stationary level before the step"
        + ("; \u2191value: that level, above the axis)" if args.zoom else ")"),
        "analytic value at t = 0+ (eqs. 15, 16)",
        "analytic stationary level at v1",
        "\u03bc limits: 4/3 \u221a(d/R) (v\u2192\u221e), 3/4 \u221a(d/R) (right after a stop)",
        "start-stop limit a2 = a1 \u221a(1 \u2212 exp(\u2212t/\u03c4))",
    ]
    max_rows = 14
    shown = case_handles[:max_rows]
    shown_labels = case_labels[:max_rows]
    if len(cases) > max_rows:
        shown_labels[-1] = f"... and {len(cases) - max_rows + 1} more cases"
    leg1 = fig.legend(shown, shown_labels, loc="lower left", bbox_to_anchor=(0.01, 0.0),
                      fontsize=8, frameon=False, title="cases", title_fontsize=8.5)
    fig.add_artist(leg1)
    fig.legend(style_handles, style_labels, loc="lower right", bbox_to_anchor=(0.99, 0.0),
               fontsize=8, frameon=False, title="lines", title_fontsize=8.5)
    title = args.title
    if title is None:
        title = ("Response to a velocity step v \u2192 v1 at t = 0 (cf. seed paper, Fig. 2)"
                 + (", similarity scales" if args.scaled else ""))
    fig.suptitle(f"{title}\n{os.path.basename(args.map)}", fontsize=11)
    n_rows = max(min(len(cases), max_rows), len(style_handles)) + 1
    bottom = min(0.42, 0.004 + 0.019 * n_rows)
    fig.tight_layout(rect=(0, bottom, 1, 0.95))
    save_figure(fig, output, args.dpi)
    print(f"{PROG}: wrote {output} ({len(cases)} case{'s' if len(cases) != 1 else ''})")
    return 0



if __name__ == "__main__":
    sys.exit(run_tool(main, PROG))
