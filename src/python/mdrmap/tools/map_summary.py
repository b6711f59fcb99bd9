# pyrun-needs: numpy h5py
"""Summarise what an mdrmap map holds, and export its rows to CSV.

Reads mdrmap-map/2 maps (a history of K segments per case,
docs/reference/map-schema.md) with /schema and /scales; everything it names comes from
the map: the case parameters and their order from /schema/cases (the loading
first), each dataset's unit from /schema, the scales from /scales (length:
a0 under load, a1 at depth; friction: a/R; time: tau). A map made before
/scales is refused with one line naming the group.

Prints, for one map:

  - provenance: schema, program version and git commit, creation time (UTC),
    command line, MPI size, units, loading, segments, samples per segment,
    whether time series are stored, and the config text;
  - how many cases are done, failed and pending;
  - the grid axes with their values and ranges (or, for a [cases] map, the
    number of cases and the range of each parameter), and the range of the
    similarity variable zeta = v tau / a1 (zeta0 = v tau / a0 under load: v
    times /scales/time over /scales/length);
  - min / median / max over the done cases of /results with their /schema
    units, mu_pre in the friction scale and, per event k, mu_before,
    mu_after, mu_peak, mu_end, a, b, a - b and D_c each in the scale of its
    /schema unit (a/R, a), with the number of undefined values (the fill
    value: holds, equal velocities, no 1/e decay); the solver's error
    estimate and wall time;
  - the worst residuals that measure numerical error (residuals/*_pre and
    *_jump: the solver against exact relations), top N by |value|, and
    separately *_end_k, the distance of segment k's end from the stationary
    state at w_k (physics, not error);
  - the failed cases with their messages (from /failures).

`--csv OUT.csv` writes every row (or those kept by `--where`): case number,
the /cases columns and each segment's wk, Tk, zeta, status, the results (bare
names), the events (<name>_<k>, e.g. mu_peak_1), analytic_<name>,
residual_<name>, scale_<name> (/scales) and the message, with a header line;
undefined values are `nan`; the results, analytic values and residuals of a
case that is not done are left empty. `--where` keeps rows by a condition on
a CSV column, e.g. `status=1`, `status!=1`, `d<=1e-3`, `zeta>10` (repeatable;
all must hold; `=` compares with a relative tolerance of 1e-9); it applies to
the printed summary too.

Usage:
    python3 -m mdrmap map_summary MAP.h5
    python3 -m mdrmap map_summary MAP.h5 --top 10 --csv rows.csv --where status=1
    python3 -m mdrmap map_summary MAP.h5 -o summary.txt

Exit codes: 0 success, 2 bad input (one line on stderr).
"""

import argparse
import csv
import os
import re
import sys

from ._maplib import (SCHEMA2, Parser, UserError, fmt, load_cases, open_map, read_masked, run_tool,
                    scale_of, scale_symbol, text)

PROG = "map_summary"
EVENT_ROWS = ["mu_before", "mu_after", "mu_peak", "mu_end", "a", "b", "a_minus_b", "D_c"]
MAX_FAILED = 20  # failed cases listed


def load(path, np, h5py):
    """The map in the form summary() and columns() read: its cases (load_cases),
    every numeric per-case dataset of /results, /events, /analytic and
    /residuals (per-event ones as <name>_<k>), in /schema's order."""
    with open_map(path, h5py, PROG) as f:
        c = load_cases(f, path, np)
        n, K = c["n"], c["K"]
        m = dict(c, version=2)
        m["attrs"] = {k: f.attrs[k] for k in f.attrs}
        m["case_cols"] = list(c["cols"])
        m.update(c["cols"])
        m["seg_cols"] = [f"{kind}{j + 1}" for j in range(K) for kind in ("w", "T")]
        for j in range(K):
            m[f"w{j + 1}"], m[f"T{j + 1}"] = c["w"][:, j], c["T"][:, j]
        m[c["zeta_name"]] = c["zeta"]
        m["derived"] = [c["zeta_name"]]
        m["groups"] = {}
        for grp in ["results", "events", "analytic", "residuals", "scales"]:
            cols = {}
            for key in c["schema"]:
                g, name = key.split("/", 1)
                if g != grp or name == "status" or key not in f:
                    continue
                ds = f[key]
                if not hasattr(ds, "dtype") or ds.dtype.kind not in "fiu":
                    continue
                if ds.shape == (n,):
                    cols[name] = read_masked(ds).astype(float)
                elif len(ds.shape) == 2 and ds.shape[0] == n:
                    x = read_masked(ds).astype(float)
                    for j in range(ds.shape[1]):
                        cols[f"{name}_{j}"] = x[:, j]
            m["groups"][grp] = cols
        grid = c["grid"]
        m["grid"] = dict(grid, log=[bool(k) for k in grid["log"]]) if grid else None
        m["timeseries"] = "timeseries" in f
        m["config_text"] = text(f["provenance/config_text"][()]) \
            if "provenance/config_text" in f else None
    return m


def unit_of(m, grp, name):
    """The /schema unit of a dataset (or of a per-event column <name>_<k>)."""
    entry = m["schema"].get(f"{grp}/{name}")
    if entry is None and name.rsplit("_", 1)[-1].isdigit():
        entry = m["schema"].get(f"{grp}/{name.rsplit('_', 1)[0]}")
    return entry[0] if entry else ""


def columns(m):
    """(header, getter) for the CSV, in order."""
    cols = [("case", None)] + [(c, m[c]) for c in m["case_cols"] + m["seg_cols"] + m["derived"]]
    cols.append(("status", m["status"]))
    for grp, prefix in [("results", ""), ("events", ""), ("analytic", "analytic_"),
                        ("residuals", "residual_"), ("scales", "scale_")]:
        for name in m["groups"].get(grp, {}):
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
    s = " ".join(f"{c}={fmt(m[c][i])}" for c in m["case_cols"] if c != "G" or m["G"][i] != 1)
    return s + " " + " ".join(f"{c}={fmt(m[c][i])}" for c in m["seg_cols"])


def stats_line(label, x, np, width):
    x = x[np.isfinite(x)]
    if x.size == 0:
        return f"  {label:<{width}}  (no finite value)"
    return (f"  {label:<{width}}  {fmt(np.min(x)):>10}  {fmt(np.median(x)):>10}  "
            f"{fmt(np.max(x)):>10}")


def provenance(m, p):
    attrs = m["attrs"]
    get = lambda k, d="?": text(attrs[k]) if k in attrs else d  # noqa: E731
    p(f"map: {m['path']}")
    p("provenance")
    schema = get("mdrmap_schema")
    p(f"  schema        {schema}" + ("" if schema == SCHEMA2 else f"  (this tool reads {SCHEMA2})"))
    p(f"  program       mdrmap {get('program_version')} (commit {get('git_commit')})")
    p(f"  created (UTC) {get('created_utc')}")
    p(f"  command line  {get('command_line')}")
    p(f"  MPI size      {get('mpi_size')}")
    p(f"  units         {get('units')}")
    p(f"  loading       {get('loading', m['loading'])}"
      f" ({'load F0 given, depth solved' if m['loading'] == 'force' else 'depth d given'})")
    p(f"  segments      {m['K']}; samples {get('samples')} per segment; time series "
      f"{'stored (/timeseries)' if m['timeseries'] else 'not stored'}")


def cases_section(m, keep, args, np, p):
    """Counts, the grid's axes (or the case list's columns), the range of zeta."""
    st, n, nk = m["status"], m["n"], int(keep.sum())
    counts = {k: int(np.sum(st[keep] == k)) for k in (1, -1, 0)}
    p("")
    if args.where:
        p(f"filter: {' and '.join(args.where)} keeps {nk} of {n} cases")
    p(f"cases: {nk}  done {counts[1]}, failed {counts[-1]}, pending {counts[0]}"
      + ("" if counts[0] == 0 else "  (resume with: mdrmap study --resume ...)"))
    g = m["grid"]
    if g:
        p(f"grid: {len(g['axes'])} axes, shape {' x '.join(str(k) for k in g['shape'])} "
          f"(C order, last axis fastest)")
        w = max(len(a) for a in g["axes"])
        for a, vals, lg in zip(g["axes"], g["values"], g["log"]):
            if vals.size <= 1:
                p(f"  {a:<{w}}  " + (f"1 value: {fmt(vals[0])}" if vals.size else "(no values stored)"))
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
    x = m["zeta"][keep]
    x = x[np.isfinite(x)]
    if x.size:
        p(f"  {m['zeta_name']} = v tau / {m['a_name']} (/scales: time over length)  "
          f"{fmt(x.min())} .. {fmt(x.max())}")


def result_rows(m, done, np):
    """(label, values) of the results, with their /schema units; mu_pre and the
    per-event metrics in the map's scales (scale_of: /scales/friction, length, ...)."""
    res, rows = m["groups"]["results"], []
    tail = [k for k in ("error_estimate", "wall_seconds") if k in res]
    for name in res:
        if name not in tail:
            unit = unit_of(m, "results", name)
            rows.append((f"{name} [{unit}]" if unit else name, res[name][done]))
    if "mu_pre" in res:
        rows.append((f"mu_pre / ({m['a_name']}/R)", res["mu_pre"][done] / m["mu_scale"][done]))
    ev = m["groups"]["events"]
    for k in range(m["K"]):
        for name in EVENT_ROWS:
            scale = scale_of(m, f"events/{name}")
            if f"{name}_{k}" not in ev or scale is None:
                continue
            x = ev[f"{name}_{k}"][done]
            undefined = int(np.sum(~np.isfinite(x)))
            label = f"event {k}: {name} / {scale_symbol(m, scale)}"
            rows.append((label + (f" ({undefined} undefined)" if undefined else ""),
                         x / m["scales"][scale][done]))
    return rows + [(f"{k} [{unit_of(m, 'results', k)}]", res[k][done]) for k in tail]


def results_section(m, keep, args, np, p):
    done = keep & (m["status"] == 1)
    nd = int(done.sum())
    p("")
    if nd == 0:
        p("results: no done case" + (" in the filter" if args.where else ""))
        return False
    p(f"results over the {nd} done cases{' in the filter' if args.where else ''}"
      f"          min      median         max")
    rows = result_rows(m, done, np)
    width = max(len(r[0]) for r in rows) if rows else 10
    for label, x in rows:
        p(stats_line(label, x, np, width))
    res = m["groups"]["results"]
    if "wall_seconds" in res:
        p(f"  total wall time of the done cases: {fmt(np.nansum(res['wall_seconds'][done]))} s")
    return True


def residuals_section(m, keep, args, np, p):
    done = keep & (m["status"] == 1)
    resid, idx = m["groups"]["residuals"], np.flatnonzero(done)
    numerical = [k for k in resid if k.endswith("_pre") or k.endswith("_jump")]
    physics = [k for k in resid if k not in numerical]
    p("")
    p("numerical error: residuals/*_pre and *_jump = (sim - analytic)/|analytic| against exact "
      "relations (eqs. 7, 9, 10, 15, 16)")
    entries = []
    for k in numerical:
        r = resid[k][idx]
        entries += [(abs(r[j]), r[j], k, int(idx[j])) for j in np.flatnonzero(np.isfinite(r))]
    if not entries:
        p("  (no residual stored)")
    else:
        p(f"  largest |residual| {fmt(max(e[0] for e in entries))} over {len(numerical)} "
          f"datasets x {idx.size} cases")
        top = sorted(entries, key=lambda e: -e[0])[: args.top]
        if top and top[0][0] > 0:
            p(f"  top {len(top)} by |value|:")
            for a, r, k, i in (e for e in top if e[0] != 0):
                p(f"    {k:<10} {fmt(r, 3):>10}   case {i}: {case_text(m, i)}")
        else:
            p("  every one is exactly 0")
    if not physics:
        return
    p("")
    p("distance from a state or a limit (physics, not error): |residual| per dataset")
    w = max(len(k) for k in physics)
    p(f"  {'':<{w}}         min      median         max   (case of the max)")
    for k in physics:
        r = np.abs(resid[k][done])
        ok = np.isfinite(r)
        if ok.any():
            i = int(idx[ok][int(np.argmax(r[ok]))])
            where = f"(case {i})" if r[ok].max() > 0 else "(all 0)"
            p(f"  {k:<{w}}  {fmt(r[ok].min()):>10}  {fmt(np.median(r[ok])):>10}  "
              f"{fmt(r[ok].max()):>10}   {where}")
    p("  *_end_k: the state at the end of segment k vs the stationary state at w_k")


def summary(m, keep, args, np, out):
    p = lambda *a: print(*a, file=out)  # noqa: E731
    provenance(m, p)
    cases_section(m, keep, args, np, p)
    if results_section(m, keep, args, np, p):
        residuals_section(m, keep, args, np, p)
    failed = np.flatnonzero(keep & (m["status"] == -1))
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
    params = set(["case"] + m["case_cols"] + m["seg_cols"] + m["derived"]
                 + [f"scale_{k}" for k in m["scales"]])
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
