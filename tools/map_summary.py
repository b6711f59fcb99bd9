#!/usr/bin/env python3
# pyrun-needs: numpy h5py
"""Summarise what an mdrmap map holds, and export its rows to CSV.

Reads both layouts (the root attribute mdrmap_schema): mdrmap-map/2 maps (a
history of K segments per case, docs/map-schema.md) and the older
mdrmap-map/1 maps (one step v -> v1 per case). For an mdrmap-map/2 map the
step-specific parts below read: the parameters are the loading (d or FN), R,
tau, G, v and each segment's w1..wK, T1..TK; the similarity variable is
zeta = v tau / a1 at depth, zeta0 = v tau / a0 under load (a0 the Hertz radius
of FN); the results are the stationary state before t = 0 (*_pre, also
mu_pre / (a/R)) and, per event k, mu_before, mu_after, mu_peak, mu_end, a, b,
a - b (in units of a/R) and D_c (in units of a), with the number of undefined
values (the fill value: holds, equal velocities, no 1/e decay); the
residuals *_pre and *_jump measure numerical error, *_end_k the distance of
segment k's end from the stationary state at w_k; the failed cases' messages
come from /failures. Per-event datasets are CSV columns <name>_<k>
(mu_peak_1, analytic_mu_ss_0, residual_mu_end_0), undefined values `nan`.

Prints, for one map (mdrmap-map/1 names):

  - provenance: schema, program version and git commit, creation time (UTC),
    command line, MPI size, units, samples per case, whether time series are
    stored, and the config text;
  - how many cases are done, failed and pending;
  - the grid axes with their values and ranges (or, for a [cases] map, the
    number of cases and the range of each parameter), and the range of the
    similarity variables zeta = v tau / a1 and zeta1 = v1 tau / a1;
  - min / median / max over the done cases of the main results (F_N, F_x, mu,
    a2 before the step, at t = 0+ and at t_end; mu / sqrt(d/R); the solver's
    error estimate and wall time);
  - the worst residuals that measure numerical error (residuals/*_pre and
    *_jump: the solver against exact relations), top N by |value|, and
    separately the residuals that measure the distance from a state or a limit
    (residuals/*_post, *_inf, mu_post_drop: physics, not error);
  - the failed cases with their messages.

`--csv OUT.csv` writes every row (or those kept by `--where`): case number,
parameters (d R tau v v1 G and v1_over_v zeta zeta1), status, the results
(bare names), analytic_<name>, residual_<name>, and the message, with a header
line; the results, analytic values and residuals of a case that is not done
are left empty. `--where` keeps rows by a condition on a CSV column, e.g. `status=1`,
`status!=1`, `d<=1e-3`, `zeta>10` (repeatable; all must hold; `=` compares
with a relative tolerance of 1e-9); it applies to the printed summary too.

Usage:
    tools/pyrun tools/map_summary.py MAP.h5
    tools/pyrun tools/map_summary.py MAP.h5 --top 10 --csv rows.csv --where status=1
    tools/pyrun tools/map_summary.py MAP.h5 -o summary.txt

Exit codes: 0 success, 2 bad input (one line on stderr).
"""

import argparse
import csv
import os
import re
import sys

from maplib import (CASE_COLS, SCHEMA1, SCHEMA2, Parser, UserError, case_columns,
                    failure_messages, fmt, load_cases, open_map, read_masked, run_tool,
                    schema_version, text)

PROG = "map_summary"
QUANT = ["FN", "Fx", "mu", "a2", "d", "a1"]
EVENT_ROWS = ["mu_before", "mu_after", "mu_peak", "mu_end", "a", "b", "a_minus_b", "d_c"]
WHEN = ["pre", "jump", "post"]
DERIVED = ["v1_over_v", "zeta", "zeta1"]
MAX_FAILED = 20  # failed cases listed


def load2(f, path, np):
    """An mdrmap-map/2 map in the form summary() and columns() read."""
    c = load_cases(f, path, np)
    n, K = c["n"], c["K"]
    m = {"path": path, "version": 2, "n": n, "K": K, "status": c["status"],
         "message": c["message"], "loading": c["loading"], "a": c["a"],
         "mu_scale": c["mu_scale"], "a_name": c["a_name"], "zeta_name": c["zeta_name"]}
    m["attrs"] = {k: f.attrs[k] for k in f.attrs}
    m["case_cols"] = list(c["cols"])
    for k, x in c["cols"].items():
        m[k] = x
    m["seg_cols"] = [f"{kind}{j + 1}" for j in range(K) for kind in ("w", "T")]
    for j in range(K):
        m[f"w{j + 1}"] = c["w"][:, j]
        m[f"T{j + 1}"] = c["T"][:, j]
    m[c["zeta_name"]] = c["zeta"]
    m["derived"] = [c["zeta_name"]]
    m["groups"] = {}
    for grp in ["results", "events", "analytic", "residuals"]:
        cols = {}
        if grp in f:
            for name, ds in f[grp].items():
                if name == "status" or not hasattr(ds, "dtype") or ds.dtype.kind not in "fiu":
                    continue
                if ds.shape == (n,):
                    cols[name] = read_masked(ds).astype(float)
                elif len(ds.shape) == 2 and ds.shape[0] == n:
                    x = read_masked(ds).astype(float)
                    for j in range(ds.shape[1]):
                        cols[f"{name}_{j}"] = x[:, j]
        m["groups"][grp] = cols
    grid = c["grid"]
    if grid:
        grid = dict(grid, log=[bool(k) for k in grid["log"]])
    m["grid"] = grid
    m["timeseries"] = "timeseries" in f
    m["config_text"] = text(f["provenance/config_text"][()]) if "provenance/config_text" in f \
        else None
    return m


def load(path, np, h5py):
    f = open_map(path, h5py, PROG)
    if schema_version(f) == 2:
        with f:
            return load2(f, path, np)
    m = {"path": path, "version": 1, "derived": DERIVED, "seg_cols": []}
    with f:
        m["attrs"] = {k: f.attrs[k] for k in f.attrs}
        n = f["results/status"].shape[0]
        m["n"] = n
        m["status"] = f["results/status"][()].astype(int)
        m["message"] = failure_messages(f, n)
        # the /cases columns: from /schema (older maps: CASE_COLS); the derived
        # variables need those of CASE_COLS in any case
        m["case_cols"] = case_columns(f)
        for c in m["case_cols"] + [c for c in CASE_COLS if c not in m["case_cols"]]:
            m[c] = f[f"cases/{c}"][()].astype(float) if f"cases/{c}" in f else np.ones(n)
        m["groups"] = {}
        for grp in ["results", "analytic", "residuals"]:
            cols = {}
            if grp in f:
                for name, ds in f[grp].items():
                    if name == "status" or not hasattr(ds, "dtype"):
                        continue
                    if ds.dtype.kind in "fiu" and ds.shape == (n,):
                        cols[name] = ds[()].astype(float)
            m["groups"][grp] = cols
        m["grid"] = None
        if "grid" in f:
            g = f["grid"]
            axes = [a.strip() for a in text(g.attrs.get("axes", "")).split(",") if a.strip()]
            shape = [int(k) for k in np.ravel(g.attrs.get("shape", []))]
            log = [bool(k) for k in np.ravel(g.attrs.get("log", [0] * len(axes)))]
            values = [g[a][()].astype(float) if a in g else np.array([]) for a in axes]
            m["grid"] = {"axes": axes, "shape": shape, "log": log, "values": values}
        m["timeseries"] = "timeseries" in f
        m["config_text"] = None
        if "provenance/config_text" in f:
            m["config_text"] = text(f["provenance/config_text"][()])
        elif "config_text" in f.attrs:
            m["config_text"] = text(f.attrs["config_text"])
    with np.errstate(divide="ignore", invalid="ignore"):
        a1 = np.sqrt(m["R"] * m["d"])
        m["v1_over_v"] = m["v1"] / m["v"]
        m["zeta"] = m["v"] * m["tau"] / a1
        m["zeta1"] = m["v1"] * m["tau"] / a1
        m["sqrt_d_over_R"] = np.sqrt(m["d"] / m["R"])
    return m


def ordered(names):
    """Result names in a stable, readable order: FN Fx mu a2 x pre jump post, then others."""
    def key(nm):
        q, _, w = nm.partition("_")
        qi = QUANT.index(q) if q in QUANT else len(QUANT)
        wi = WHEN.index(w) if w in WHEN else len(WHEN)
        return (qi, wi, nm)
    return sorted(names, key=key)


def columns(m):
    """(header, getter) for the CSV, in order."""
    cols = [("case", None)] + [(c, m[c]) for c in m["case_cols"] + m["seg_cols"] + m["derived"]]
    cols.append(("status", m["status"]))
    for grp, prefix in [("results", ""), ("events", ""), ("analytic", "analytic_"),
                        ("residuals", "residual_")]:
        for name in ordered(m["groups"].get(grp, {})):
            cols.append((prefix + name, m["groups"][grp][name]))
    return cols


def parse_where(specs, m, np):
    keep = np.ones(m["n"], dtype=bool)
    cols = dict(columns(m))
    cols["case"] = np.arange(m["n"], dtype=float)
    for spec in specs or []:
        mt = re.match(r"^\s*([A-Za-z_][\w]*)\s*(<=|>=|!=|==|=|<|>)\s*(\S+)\s*$", spec)
        if not mt:
            raise UserError(f"--where {spec!r}: expected COLUMN OP VALUE with OP one of "
                            f"= != < <= > >= (e.g. status=1)")
        name, op, val = mt.groups()
        if name not in cols:
            raise UserError(f"--where {spec}: no column {name!r} (columns: "
                            f"{', '.join(k for k in cols)})")
        try:
            x = float(val)
        except ValueError:
            raise UserError(f"--where {spec}: {val!r} is not a number") from None
        c = np.asarray(cols[name], dtype=float)
        with np.errstate(invalid="ignore"):
            eq = np.isclose(c, x, rtol=1e-9, atol=0 if x != 0 else 1e-300)
            keep &= {"=": eq, "==": eq, "!=": ~eq, "<": c < x, "<=": (c < x) | eq,
                     ">": c > x, ">=": (c > x) | eq}[op]
    return keep


def case_text(m, i):
    if m["version"] == 2:
        s = " ".join(f"{c}={fmt(m[c][i])}" for c in m["case_cols"] if c != "G" or m["G"][i] != 1)
        return s + " " + " ".join(f"{c}={fmt(m[c][i])}" for c in m["seg_cols"])
    s = (f"d={fmt(m['d'][i])} R={fmt(m['R'][i])} tau={fmt(m['tau'][i])} "
         f"v={fmt(m['v'][i])} v1={fmt(m['v1'][i])}")
    if m["G"][i] != 1:
        s += f" G={fmt(m['G'][i])}"
    return s


def stats_line(label, x, np, width):
    x = x[np.isfinite(x)]
    if x.size == 0:
        return f"  {label:<{width}}  (no finite value)"
    return (f"  {label:<{width}}  {fmt(np.min(x)):>10}  {fmt(np.median(x)):>10}  "
            f"{fmt(np.max(x)):>10}")


def summary(m, keep, args, np, out):
    p = lambda *a: print(*a, file=out)  # noqa: E731
    attrs = m["attrs"]
    get = lambda k, d="?": text(attrs[k]) if k in attrs else d  # noqa: E731
    p(f"map: {m['path']}")
    p("provenance")
    schema = get("mdrmap_schema")
    p(f"  schema        {schema}" + ("" if schema in (SCHEMA1, SCHEMA2) else
                                       f"  (this tool reads {SCHEMA2} and {SCHEMA1})"))
    p(f"  program       mdrmap {get('program_version')} (commit {get('git_commit')})")
    p(f"  created (UTC) {get('created_utc')}")
    p(f"  command line  {get('command_line')}")
    p(f"  MPI size      {get('mpi_size')}")
    p(f"  units         {get('units')}")
    if m["version"] == 2:
        p(f"  loading       {get('loading', m['loading'])}"
          f" ({'FN given, depth solved' if m['loading'] == 'force' else 'depth d given'})")
        p(f"  segments      {m['K']}; samples {get('samples')} per segment; time series "
          f"{'stored (/timeseries)' if m['timeseries'] else 'not stored'}")
    else:
        p(f"  samples       {get('samples')} per case; time series "
          f"{'stored (/timeseries)' if m['timeseries'] else 'not stored'}")

    st = m["status"]
    n = m["n"]
    nk = int(keep.sum())
    counts = {k: int(np.sum(st[keep] == k)) for k in (1, -1, 0)}
    p("")
    if args.where:
        p(f"filter: {' and '.join(args.where)} keeps {nk} of {n} cases")
    p(f"cases: {nk}  done {counts[1]}, failed {counts[-1]}, pending {counts[0]}"
      + ("" if counts[0] == 0 else "  (resume with: mdrmap study --resume ...)"))

    g = m["grid"]
    if g:
        dims = " x ".join(str(k) for k in g["shape"])
        p(f"grid: {len(g['axes'])} axes, shape {dims} (C order, last axis fastest)")
        w = max(len(a) for a in g["axes"])
        for a, vals, lg in zip(g["axes"], g["values"], g["log"]):
            if vals.size == 0:
                p(f"  {a:<{w}}  (no values stored)")
                continue
            if vals.size == 1:
                p(f"  {a:<{w}}  1 value: {fmt(vals[0])}")
                continue
            listing = ", ".join(fmt(v) for v in vals) if vals.size <= 8 else \
                f"{fmt(vals.min())} .. {fmt(vals.max())}"
            p(f"  {a:<{w}}  {vals.size} values{' (log)' if lg else ''}: {listing}")
    else:
        p(f"case list (no /grid): {n} cases")
        for c in m["case_cols"] + m["seg_cols"]:
            u = np.unique(m[c])
            listing = ", ".join(fmt(v) for v in u) if u.size <= 8 else \
                f"{fmt(u.min())} .. {fmt(u.max())}"
            p(f"  {c:<4}  {u.size} distinct: {listing}")
    sel = keep
    zetas = [("zeta", "zeta  = v tau / a1 "), ("zeta1", "zeta1 = v1 tau / a1")]
    if m["version"] == 2:
        zetas = [(m["zeta_name"], f"{m['zeta_name']} = v tau / {m['a_name']}"
                  + (" (a0: Hertz radius of FN)" if m["a_name"] == "a0" else " (a1 = sqrt(R d))"))]
    for c, label in zetas:
        x = m[c][sel]
        x = x[np.isfinite(x)]
        if x.size:
            p(f"  {label}  {fmt(x.min())} .. {fmt(x.max())}")

    done = keep & (st == 1)
    nd = int(done.sum())
    res = m["groups"]["results"]
    p("")
    if nd == 0:
        p("results: no done case" + (" in the filter" if args.where else ""))
    else:
        p(f"results over the {nd} done cases{' in the filter' if args.where else ''}"
          f"          min      median         max")
        rows = []
        for q in QUANT:
            for w in WHEN:
                name = f"{q}_{w}"
                if name in res:
                    rows.append((name, res[name][done]))
        if m["version"] == 2:
            an = m["a_name"]
            if "mu_pre" in res:
                rows.append((f"mu_pre / ({an}/R)", res["mu_pre"][done] / m["mu_scale"][done]))
            ev = m["groups"]["events"]
            for k in range(m["K"]):
                for name in EVENT_ROWS:
                    if f"{name}_{k}" not in ev:
                        continue
                    x = ev[f"{name}_{k}"][done]
                    scale = m["a"][done] if name == "d_c" else m["mu_scale"][done]
                    unit = an if name == "d_c" else f"{an}/R"
                    undefined = int(np.sum(~np.isfinite(x)))
                    label = f"event {k}: {name} / {unit}"
                    if undefined:
                        label += f" ({undefined} undefined)"
                    rows.append((label, x / scale))
        for w in WHEN if m["version"] == 1 else []:
            if f"mu_{w}" in res:
                rows.append((f"mu_{w} / sqrt(d/R)", res[f"mu_{w}"][done] / m["sqrt_d_over_R"][done]))
        for name in ["error_estimate", "wall_seconds"]:
            if name in res:
                rows.append((name, res[name][done]))
        width = max(len(r[0]) for r in rows) if rows else 10
        for label, x in rows:
            p(stats_line(label, x, np, width))
        if "wall_seconds" in res:
            p(f"  total wall time of the done cases: {fmt(np.nansum(res['wall_seconds'][done]))} s")

        resid = m["groups"]["residuals"]
        numerical = [k for k in ordered(resid) if k.endswith("_pre") or k.endswith("_jump")]
        physics = [k for k in ordered(resid) if k not in numerical]
        p("")
        p("numerical error: residuals/*_pre and *_jump = (sim - analytic)/|analytic| against exact "
          "relations (eqs. 7, 9, 10, 15, 16)")
        idx = np.flatnonzero(done)
        entries = []
        for k in numerical:
            r = resid[k][idx]
            for j in np.flatnonzero(np.isfinite(r)):
                entries.append((abs(r[j]), r[j], k, int(idx[j])))
        if not entries:
            p("  (no residual stored)")
        else:
            worst = max(e[0] for e in entries)
            p(f"  largest |residual| {fmt(worst)} over {len(numerical)} datasets x {nd} cases")
            top = sorted(entries, key=lambda e: -e[0])[: args.top]
            if top and top[0][0] > 0:
                p(f"  top {len(top)} by |value|:")
                for a, r, k, i in top:
                    if a == 0:
                        break
                    p(f"    {k:<10} {fmt(r, 3):>10}   case {i}: {case_text(m, i)}")
            else:
                p("  every one is exactly 0")
        if physics:
            p("")
            p("distance from a state or a limit (physics, not error): |residual| per dataset")
            w = max(len(k) for k in physics)
            p(f"  {'':<{w}}         min      median         max   (case of the max)")
            for k in physics:
                r = np.abs(resid[k][done])
                ok = np.isfinite(r)
                if not ok.any():
                    continue
                i = int(idx[ok][int(np.argmax(r[ok]))])
                where = f"(case {i})" if r[ok].max() > 0 else "(all 0)"
                p(f"  {k:<{w}}  {fmt(r[ok].min()):>10}  {fmt(np.median(r[ok])):>10}  "
                  f"{fmt(r[ok].max()):>10}   {where}")
            if m["version"] == 2:
                p("  *_end_k: the state at the end of segment k vs the stationary state at w_k")
            else:
                p("  *_post: state at t_end vs the stationary state at v1; *_inf: before the step "
                  "vs v -> inf (eqs. 12-14); mu_post_drop: mu at t = 0+ vs 3/4 sqrt(d/R)")

    failed = np.flatnonzero(keep & (st == -1))
    if failed.size:
        p("")
        p(f"failed cases ({failed.size}):")
        for i in failed[:MAX_FAILED]:
            p(f"  case {i}: {case_text(m, i)}: {m['message'][i] or '(no message)'}")
        if failed.size > MAX_FAILED:
            p(f"  ... and {failed.size - MAX_FAILED} more (all of them: --csv OUT.csv --where status=-1)")

    if m["config_text"] is not None and not args.no_config:
        p("")
        p("config text:")
        for line in m["config_text"].rstrip("\n").splitlines():
            p(f"  | {line}")


def write_csv(m, keep, path, np):
    cols = columns(m)
    params = set(["case"] + m["case_cols"] + m["seg_cols"] + m["derived"])
    header = [c for c, _ in cols] + ["message"]
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        for i in np.flatnonzero(keep):
            row = [str(i)]
            done = m["status"][i] == 1
            for name, arr in cols[1:]:
                x = arr[i]
                if name == "status":
                    row.append(str(int(x)))
                elif not done and name not in params and name != "wall_seconds":
                    row.append("")  # not computed: empty, not the stored 0
                else:
                    row.append(repr(float(x)))
            row.append(m["message"][i])
            w.writerow(row)
    return int(keep.sum()), len(header)


def main(argv=None):
    ap = Parser(prog=PROG, description=__doc__,
                formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("map", help="mdrmap map (.h5)")
    ap.add_argument("-o", "--output", metavar="FILE", default=None,
                    help="write the summary to FILE instead of stdout")
    ap.add_argument("--csv", metavar="OUT.csv", default=None,
                    help="write every row (parameters, status, results, analytic, residuals, "
                         "message) with a header")
    ap.add_argument("--where", action="append", metavar="COND",
                    help="keep rows where COND holds, e.g. status=1, d<=1e-3 (repeatable)")
    ap.add_argument("--top", type=int, default=5, metavar="N",
                    help="how many of the worst numerical residuals to list (default 5)")
    ap.add_argument("--no-config", action="store_true", help="do not print the config text")
    ap.add_argument("--quiet", action="store_true",
                    help="print no summary (only the line saying what --csv wrote)")
    args = ap.parse_args(argv)
    if args.top < 0:
        raise UserError(f"--top {args.top}: must be >= 0")
    for path in (args.csv, args.output):
        if path:
            outdir = os.path.dirname(os.path.abspath(path))
            if not os.path.isdir(outdir):
                raise UserError(f"cannot write {path}: no such directory {outdir}")

    import numpy as np
    import h5py

    m = load(args.map, np, h5py)
    keep = parse_where(args.where, m, np)
    if args.output:
        try:
            with open(args.output, "w") as out:
                summary(m, keep, args, np, out)
        except OSError as e:
            raise UserError(f"cannot write {args.output}: {e.strerror or e}") from None
        print(f"{PROG}: wrote {args.output}")
    elif not args.quiet:
        summary(m, keep, args, np, sys.stdout)
    if args.csv:
        try:
            rows, ncol = write_csv(m, keep, args.csv, np)
        except OSError as e:
            raise UserError(f"cannot write {args.csv}: {e.strerror or e}") from None
        gap = "" if args.quiet or args.output else "\n"
        print(f"{gap}{PROG}: wrote {args.csv} ({rows} rows, {ncol} columns)")
    return 0



if __name__ == "__main__":
    sys.exit(run_tool(main, PROG))
