# pyrun-needs: numpy matplotlib
"""The records of a fit and the fitted model: what `mdrmap fit --output
FIT.json` wrote (its "records": per record the rows' t and, per fitted
column, the data and the model at the fitted values). One column of panels
per record: per measured quantity the data (points) and the model (line)
against t, and below them the residuals (data - model) of each quantity
relative to its largest |data|.

Usage:
    mdrmap fit --data a.csv --data b.csv --free R,aT --d 0.1 --tau 1 --output fit.json
    python3 -m mdrmap plot_fit fit.json -o fit.png

Exit codes: 0 success, 2 bad input (one line on stderr).
"""
import json

from ._maplib import Parser, UserError, save_figure

PROG = "plot_fit"


def read(path):
    try:
        with open(path, encoding="utf-8") as f:
            fit = json.load(f)
    except OSError as e:
        raise UserError(f"cannot read {path}: {e.strerror or e}") from None
    except ValueError as e:
        raise UserError(f"{path}: not JSON ({e})") from None
    if not isinstance(fit, dict) or not fit.get("records"):
        raise UserError(f"{path}: no records; is it the output of mdrmap fit?")
    return fit


def figure(fit, plt, np):
    records = fit["records"]
    rows = max(len(r["columns"]) for r in records) + 1
    fig, axes = plt.subplots(rows, len(records), figsize=(4.5 * len(records), 2.6 * rows),
                             squeeze=False, sharex="col")
    title = ", ".join(f"{n} = {p['value']:.4g}" for n, p in fit["parameters"].items())
    fig.suptitle(f"fit: {title}  (rms {fit['rms']:.3g})")
    for j, rec in enumerate(records):
        t = np.asarray(rec["t"], float)
        for i, (name, col) in enumerate(rec["columns"].items()):
            data = np.array([np.nan if x is None else x for x in col["data"]], float)
            model = np.array([np.nan if x is None else x for x in col["model"]], float)
            ax = axes[i][j]
            ax.plot(t, data, "o", ms=3, label="data")
            ax.plot(t, model, "-", label="model")
            ax.set_ylabel(name)
            if i == 0:
                ax.set_title(rec["file"].rsplit("/", 1)[-1], fontsize=9)
                ax.legend(fontsize=8)
            scale = np.nanmax(np.abs(data))
            axes[-1][j].plot(t, (data - model) / scale, ".-", lw=0.5, label=name)
        axes[-1][j].axhline(0.0, color="grey", lw=0.5)
        axes[-1][j].set_ylabel("residual / max|data|")
        axes[-1][j].set_xlabel("t")
        axes[-1][j].legend(fontsize=8)
    fig.tight_layout()
    return fig


def main(argv=None):
    p = Parser(prog=PROG, description=__doc__.split("\n\n")[0])
    p.add_argument("fit", help="the JSON that mdrmap fit --output wrote")
    p.add_argument("-o", "--output", required=True, help="the figure (PNG, PDF, SVG, ...)")
    p.add_argument("--dpi", type=int, default=120)
    a = p.parse_args(argv)
    fit = read(a.fit)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    save_figure(figure(fit, plt, np), a.output, a.dpi)
    return 0
