#!/usr/bin/env python3
# pyrun-needs: matplotlib
"""Work-precision plot of the mdrmap benchmark (error against time, log-log).

Reads the summary CSV written by mdrmap_bench (tools/bench.sh writes it to
out/bench/bench.csv) and writes a PNG with three panels:

  1. all scenes of the case set: largest case error over the scenes;
  2. the baseline subset: largest case error;
  3. the baseline subset: median case error (where the fixed-step baseline's
     typical accuracy shows).

x is the median wall time of one solver call per scene. Errors that are
exactly zero (the reference itself) are drawn as hollow markers at the bottom
of the axis.

With --load, reads the CSV of mdrmap_bench_load (out/bench/load.csv) instead
and draws the load-control work-precision comparison: one panel per history
of its side-by-side part, the fixed-step load baseline's a0/dx ladder against
the load solver's rtol ladder and fixed-resolution settings, each baseline
point annotated with its cost ratio at equal error.

Usage:
    tools/pyrun tools/plot_bench.py out/bench/bench.csv -o out/bench/work_precision.png
    tools/pyrun tools/plot_bench.py --load out/bench/load.csv -o out/bench/load_work_precision.png
"""

import argparse
import csv
import math
import sys

STYLE = {  # family: (label, colour, marker)
    "exact": ("exact (continuum), rtol ladder", "tab:blue", "o"),
    "auto": ("simulate default (auto, rtol 1e-4)", "black", "*"),
    "row": ("row (N = 0), rtol ladder", "tab:green", "s"),
    "baseline": ("fixed-step baseline, a1/dx ladder", "tab:purple", "X"),
}
ZERO_FLOOR = 1e-17  # where exact zeros are drawn


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit(f"plot_bench: {path} has no rows")
    need = {"solver", "setting", "subset", "median_time_s", "max_error", "median_error"}
    missing = need - set(rows[0])
    if missing:
        raise SystemExit(f"plot_bench: {path} lacks columns {sorted(missing)}")
    return rows


def number(text):
    try:
        x = float(text)
    except ValueError:
        return math.nan
    return x


def short_label(setting):
    """'rtol=1e-04' -> '1e-4', 'a1/dx=500' -> '500'."""
    value = setting.split("=", 1)[-1]
    if "e-0" in value:
        value = value.replace("e-0", "e-")
    return value


def panel(ax, rows, subset, column, title):
    floor_used = False
    for family, (label, colour, marker) in STYLE.items():
        pts = [r for r in rows if r["solver"] == family and r["subset"] == subset]
        pts = [r for r in pts if not math.isnan(number(r["median_time_s"]))]
        if not pts:
            continue
        t = [1e3 * number(r["median_time_s"]) for r in pts]
        e = [number(r[column]) for r in pts]
        shown = [x if x > 0 else ZERO_FLOOR for x in e]
        floor_used |= any(x == 0 for x in e)
        ax.plot(t, shown, color=colour, lw=1.2, alpha=0.7, zorder=2)
        filled = [i for i, x in enumerate(e) if x > 0]
        hollow = [i for i, x in enumerate(e) if not x > 0]
        ax.scatter([t[i] for i in filled], [shown[i] for i in filled], color=colour,
                   marker=marker, s=70 if marker == "*" else 34, label=label, zorder=3)
        if hollow:
            ax.scatter([t[i] for i in hollow], [shown[i] for i in hollow], facecolors="none",
                       edgecolors=colour, marker=marker, s=34, zorder=3)
        if family != "auto":  # one label per distinct point: "1e-2,1e-3" where they coincide
            groups = {}
            for ti, ei, r in zip(t, shown, pts):
                key = (round(4 * math.log10(ti)), round(4 * math.log10(ei)))  # quarter decades
                groups.setdefault(key, (ti, ei, []))[2].append(short_label(r["setting"]))
            for ti, ei, names in groups.values():
                ax.annotate(",".join(names), (ti, ei), textcoords="offset points",
                            xytext=(4, 3), fontsize=6.5, color=colour)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("median wall time per scene [ms]")
    ax.set_ylabel("max case error" if column == "max_error" else "median case error")
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="major", alpha=0.3)
    ax.grid(True, which="minor", alpha=0.08)
    if floor_used:
        ax.text(0.02, 0.02, f"hollow: error exactly 0, drawn at {ZERO_FLOOR:g}",
                transform=ax.transAxes, fontsize=7, color="0.3")


LOAD_STYLE = {  # (part, rtol given): (label, colour, marker)
    ("baseline", False): ("fixed-step load baseline, a0/dx ladder", "tab:purple", "X"),
    ("load", True): ("load solver, rtol ladder (with estimate)", "tab:green", "s"),
    ("load", False): ("load solver, fixed a/dx and h/tau", "tab:orange", "^"),
}


def load_label(row):
    """'baseline a0/dx=400' -> '400', 'load rtol=1e-3' -> '1e-3', 'load a/dx=4 h/tau=0.01' -> '4,0.01'."""
    parts = row["setting"].split()[1:]
    return ",".join(p.split("=", 1)[-1] for p in parts)


def plot_load(args, plt):
    with open(args.csv, newline="") as f:
        rows = list(csv.DictReader(f))
    need = {"part", "setting", "case", "rtol", "error", "median_seconds", "failed", "ratio",
            "ratio_how"}
    if not rows or need - set(rows[0]):
        raise SystemExit(f"plot_bench: {args.csv} is not a load.csv of mdrmap_bench_load")
    rows = [r for r in rows if r["failed"] == "0" and r["part"] in ("load", "baseline")]
    cases = list(dict.fromkeys(r["case"] for r in rows))
    if not cases:
        raise SystemExit(f"plot_bench: {args.csv} has no side-by-side rows")
    fig, axes = plt.subplots(1, len(cases), figsize=(6 * len(cases), 5.6), squeeze=False)
    for ax, case in zip(axes[0], cases):
        for (part, adaptive), (label, colour, marker) in LOAD_STYLE.items():
            pts = [r for r in rows if r["case"] == case and r["part"] == part and
                   (number(r["rtol"]) > 0) == adaptive]
            pts = [r for r in pts if number(r["error"]) > 0]
            if not pts:
                continue
            t = [1e3 * number(r["median_seconds"]) for r in pts]
            e = [number(r["error"]) for r in pts]
            ax.plot(t, e, color=colour, lw=1.2, alpha=0.7, zorder=2,
                    ls="-" if part == "baseline" or adaptive else ":")
            ax.scatter(t, e, color=colour, marker=marker, s=34, label=label, zorder=3)
            for ti, ei, r in zip(t, e, pts):
                text = load_label(r)
                if part == "baseline" and r["ratio"]:
                    how = r["ratio_how"]
                    ratio = float(r["ratio"])
                    text += f" ({'>=' if how == 'bound' else ''}{ratio:.3g}x" + \
                        (", extrap." if how == "extrap" else "") + ")"
                ax.annotate(text, (ti, ei), textcoords="offset points", xytext=(4, 3),
                            fontsize=6.5, color=colour)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("median wall time per call [ms]")
        ax.set_ylabel("case error against the reference")
        ax.set_title(case, fontsize=10)
        ax.grid(True, which="major", alpha=0.3)
        ax.grid(True, which="minor", alpha=0.08)
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=8.5, frameon=False)
    title = ("mdrmap load control: kelvin_load vs the fixed-step baseline "
             "(baseline points: cost ratio at equal error)")
    if args.title:
        title += "\n" + args.title
    fig.suptitle(title, fontsize=11)
    fig.tight_layout(rect=(0, 0.07, 1, 0.93))
    fig.savefig(args.output, dpi=args.dpi)
    print(f"plot_bench: wrote {args.output}")
    return 0


def main(argv=None):
    ap = argparse.ArgumentParser(
        description="Work-precision plot (error vs time, log-log) of mdrmap_bench's CSV.")
    ap.add_argument("csv", help="summary CSV written by mdrmap_bench (bench.csv)")
    ap.add_argument("-o", "--output", default="work_precision.png", help="PNG to write")
    ap.add_argument("--title", default="", help="figure title (e.g. the machine)")
    ap.add_argument("--dpi", type=int, default=110)
    ap.add_argument("--load", action="store_true",
                    help="the CSV is mdrmap_bench_load's load.csv: plot the load-control comparison")
    args = ap.parse_args(argv)

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    if args.load:
        return plot_load(args, plt)

    rows = read_rows(args.csv)
    n_all = max((int(r["cases"]) for r in rows if r["subset"] == "all"), default=0)
    n_sub = max((int(r["cases"]) for r in rows if r["subset"] == "baseline-subset"), default=0)

    fig, axes = plt.subplots(1, 3, figsize=(17, 5.6))
    panel(axes[0], rows, "all", "max_error", f"all {n_all} scenes: largest error")
    panel(axes[1], rows, "baseline-subset", "max_error",
          f"baseline subset ({n_sub} scenes): largest error")
    panel(axes[2], rows, "baseline-subset", "median_error",
          f"baseline subset ({n_sub} scenes): median error")
    handles, labels = [], []
    for ax in axes:
        for h, l in zip(*ax.get_legend_handles_labels()):
            if l not in labels:
                handles.append(h)
                labels.append(l)
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=8.5, frameon=False)
    title = "mdrmap work-precision: error against the continuum solution vs time per scene"
    if args.title:
        title += "\n" + args.title
    fig.suptitle(title, fontsize=11)
    fig.tight_layout(rect=(0, 0.08, 1, 0.95))
    fig.savefig(args.output, dpi=args.dpi)
    print(f"plot_bench: wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
