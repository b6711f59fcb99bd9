#!/usr/bin/env python3
"""Check that an mdrmap friction map has the documented layout.

Usage: check_map.py MAP.h5 [--complete] [--expect-failed N] [--quiet]

Checks every dataset of the map's schema, mdrmap-map/2 (docs/reference/map-schema.md)
or mdrmap-map/1 (names, shapes, types), the root provenance attributes, that
status holds only -1/0/1, that no value is NaN or infinite, and that done
cases carry a positive normal force. For mdrmap-map/2 also: /scales (length,
depth, force, friction, time); the fill value
(9.969209968386869e36) appears only in events/{a,b,a_minus_b,D_c,healing}, which carry
it as their attribute _FillValue; /timeseries/segment numbers the segments;
every failed case has a message in /failures. With --complete, also that no
case is pending. Exits 0 when the map is valid, 1 otherwise, printing one
line per problem.
"""
import argparse
import sys

import h5py
import numpy as np

QUANT = ["FN", "Fx", "mu", "a2"]
WHEN = ["pre", "jump", "post"]
LIMITS = ["FN_inf", "Fx_inf", "mu_inf", "mu_post_drop"]
ROOT_ATTRS = ["mdrmap_schema", "program_version", "git_commit", "created_utc", "command_line",
              "mpi_size", "units", "config_text", "n_cases", "samples"]


def expected_datasets(n, samples, timeseries):
    d = {f"cases/{c}": ((n,), "f8") for c in ["d", "R", "tau", "v", "v1", "G"]}
    for g in ["results", "analytic", "residuals"]:
        for w in WHEN:
            for q in QUANT:
                d[f"{g}/{q}_{w}"] = ((n,), "f8")
    for lim in LIMITS:
        d[f"analytic/{lim}"] = ((n,), "f8")
        d[f"residuals/{lim}"] = ((n,), "f8")
    d["results/error_estimate"] = ((n,), "f8")
    d["results/wall_seconds"] = ((n,), "f8")
    d["results/status"] = ((n,), "i1")
    d["results/message"] = ((n,), "S")
    if timeseries:
        for s in ["t", "FN", "Fx", "mu", "a2"]:
            d[f"timeseries/{s}"] = ((n, samples), "f8")
    return d


FILL = 9.969209968386869e36
ROOT_ATTRS2 = ["mdrmap_schema", "n_cases", "segments", "samples", "loading", "program_version",
               "git_commit", "created_utc", "command_line", "mpi_size", "units"]
EVENTS = ["t", "FN_after", "Fx_after", "mu_after", "a2_after", "mu_before", "mu_peak", "t_peak",
          "slip_peak", "FN_end", "Fx_end", "mu_end", "a2_end", "a", "b", "a_minus_b", "D_c"]
# D_c's name in maps written before the output table (read as D_c by the module)
OLD_NAMES = {"D_c": "d_c"}
# the extrema and the healing of a reslide (issue 32): in maps written since
EXTREMA = ["mu_max", "t_max", "slip_max", "mu_min", "t_min", "slip_min", "healing"]
FILLED = {"events/a", "events/b", "events/a_minus_b", "events/D_c", "events/d_c",
          "events/healing"}
SCALES = ["length", "depth", "force", "friction", "time"]  # /scales (docs/reference/map-schema.md)


def expected_datasets2(n, k, s, load, timeseries, indenter=("R",), extrema=True, old=False):
    """`load`: the name of the prescribed load's /cases column (F0, or FN in a
    map written before it was named F0), or None at fixed depth; `indenter`:
    the profile's columns (R of the parabola, beta of the cone, n and A of a
    power law); `old`: a map with the old output names (OLD_NAMES)."""
    q = ["FN", "Fx", "mu", "a2"] + (["d", "a1"] if load else [])
    d = {f"cases/{c}": ((n,), "f8") for c in [load or "d", *indenter, "tau", "G", "v"]}
    d["cases/w"] = ((n, k), "f8")
    d["cases/T"] = ((n, k), "f8")
    d["results/status"] = ((n,), "i1")
    d["results/error_estimate"] = ((n,), "f8")
    d["results/wall_seconds"] = ((n,), "f8")
    for x in q:
        d[f"results/{x}_pre"] = ((n,), "f8")
        d[f"analytic/{x}_pre"] = ((n,), "f8")
        d[f"analytic/{x}_ss"] = ((n, k), "f8")
        d[f"residuals/{x}_pre"] = ((n,), "f8")
        d[f"residuals/{x}_end"] = ((n, k), "f8")
    if not load:
        for x in q:
            d[f"analytic/{x}_jump"] = ((n,), "f8")
            d[f"residuals/{x}_jump"] = ((n,), "f8")
    for m in EVENTS + (["d_end", "a1_end"] if load else []) + (EXTREMA if extrema else []):
        d[f"events/{OLD_NAMES.get(m, m) if old else m}"] = ((n, k), "f8")
    if timeseries:
        for x in ["t"] + q:
            d[f"timeseries/{x}"] = ((n, k * s), "f8")
        d["timeseries/segment"] = ((k * s,), "i4")
    for x in SCALES:
        d[f"scales/{x}"] = ((n,), "f8")
    d["failures/case"] = (None, "u8")
    d["failures/message"] = (None, "S")
    return d


def check_grid_status(f, n, problems):
    """Checks /grid (its shape multiplies to the n cases, one dataset per axis of
    its length) and /results/status (only -1, 0, 1), appending to problems;
    returns the status."""
    if "grid" in f:
        g = f["grid"]
        axes = g.attrs["axes"]
        axes = (axes.decode() if isinstance(axes, bytes) else str(axes)).split(",")
        shape = tuple(int(x) for x in g.attrs["shape"])
        if int(np.prod(shape)) != n:
            problems.append(f"grid shape {shape} does not multiply to {n} cases")
        for a, m in zip(axes, shape):
            if a not in g or g[a].shape != (m,):
                problems.append(f"/grid/{a} missing or not of length {m}")
    status = f["results/status"][()]
    bad = set(np.unique(status)) - {-1, 0, 1}
    if bad:
        problems.append(f"status holds values {sorted(bad)}")
    return status


def check_datasets2(f, expected, problems):
    """Each expected dataset: present, of its shape and type, finite, the fill
    value only where the schema allows it."""
    for name, (shape, kind) in expected.items():
        if name not in f:
            problems.append(f"missing dataset /{name}")
            continue
        ds = f[name]
        if shape is not None and ds.shape != shape:
            problems.append(f"/{name} has shape {ds.shape}, expected {shape}")
        if kind == "S":
            if ds.dtype.kind not in "SO":
                problems.append(f"/{name} is {ds.dtype}, expected strings")
            continue
        if ds.dtype != np.dtype(kind):
            problems.append(f"/{name} is {ds.dtype}, expected {kind}")
            continue
        if ds.dtype.kind == "f":
            x = ds[()]
            if not np.all(np.isfinite(x)):
                problems.append(f"/{name} holds NaN or inf")
            filled = x == FILL
            if name in FILLED:
                fv = ds.attrs.get("_FillValue")
                if fv is None or float(np.ravel(fv)[0]) != FILL:
                    problems.append(f"/{name} has no attribute _FillValue = {FILL!r}")
            elif np.any(filled) and not name.startswith(("results/", "analytic/", "residuals/",
                                                          "timeseries/", "events/")):
                problems.append(f"/{name} holds the fill value")


def check2(f, complete, expect_failed):
    problems = []
    for a in ROOT_ATTRS2:
        if a not in f.attrs:
            problems.append(f"missing root attribute {a}")
    if problems:
        return problems, {}
    n, k, s = (int(f.attrs[a]) for a in ("n_cases", "segments", "samples"))
    # the prescribed load: /cases/F0 (/cases/FN in a map of an earlier mdrmap)
    load = next((c for c in ("F0", "FN") if f"cases/{c}" in f), None)
    loading = f.attrs["loading"]
    loading = loading.decode() if isinstance(loading, bytes) else str(loading)
    if loading != ("force" if load else "depth"):
        problems.append(f"root attribute loading is {loading!r} but /cases has "
                        f"{load or 'd'}")
    indenter = [c for c in ("R", "beta", "n", "A") if f"cases/{c}" in f] or ["R"]
    check_datasets2(f, expected_datasets2(n, k, s, load, "timeseries" in f, indenter,
                                          "events/mu_max" in f,
                                          "events/d_c" in f and "events/D_c" not in f), problems)
    status = check_grid_status(f, n, problems)
    done = status == 1
    if "results/FN_pre" in f and np.any(f["results/FN_pre"][()][done] <= 0):
        problems.append("a done case has F_N <= 0 before t = 0")
    for name in ("scales/length", "scales/force", "scales/friction"):
        if name in f and np.any(f[name][()][done] <= 0):
            problems.append(f"a done case has /{name} <= 0")
    if done.any():
        for name in ("cases/w", "events/mu_after", "events/D_c", "events/d_c"):
            if name in f and name not in FILLED and np.any(f[name][()][done] == FILL):
                problems.append(f"/{name} holds the fill value in a done case")
    if "timeseries/segment" in f:
        want = np.repeat(np.arange(k), s)
        if not np.array_equal(f["timeseries/segment"][()], want):
            problems.append("/timeseries/segment is not 0..K-1, each S times")
    failed = np.flatnonzero(status == -1)
    if "failures/case" in f and "failures/message" in f:
        fc = [int(i) for i in f["failures/case"][()]]
        msgs = dict(zip(fc, f["failures/message"][()]))
        for i in failed:
            if i not in msgs or len(msgs[i]) == 0:
                problems.append(f"failed case {i} has no message in /failures")
                break
    if expect_failed is not None and failed.size != expect_failed:
        problems.append(f"{failed.size} failed cases, expected {expect_failed}")
    if complete and np.any(status == 0):
        problems.append(f"{int(np.sum(status == 0))} cases are still pending")
    counts = {"cases": n, "segments": k, "done": int(np.sum(status == 1)),
              "failed": int(failed.size), "pending": int(np.sum(status == 0))}
    return problems, counts


def check(path, complete, expect_failed=None):
    problems = []
    with h5py.File(path, "r") as f:
        schema = f.attrs.get("mdrmap_schema", b"")
        schema = schema.decode() if isinstance(schema, bytes) else str(schema)
        if schema == "mdrmap-map/2":
            return check2(f, complete, expect_failed)
        for a in ROOT_ATTRS:
            if a not in f.attrs:
                problems.append(f"missing root attribute {a}")
        if problems:
            return problems, {}
        schema = f.attrs["mdrmap_schema"]
        schema = schema.decode() if isinstance(schema, bytes) else str(schema)
        if schema != "mdrmap-map/1":
            problems.append(f"schema is {schema}, expected mdrmap-map/1")
        n = int(f.attrs["n_cases"])
        samples = int(f.attrs["samples"])
        timeseries = bool(int(f.attrs.get("timeseries", 0)))
        for name, (shape, kind) in expected_datasets(n, samples, timeseries).items():
            if name not in f:
                problems.append(f"missing dataset /{name}")
                continue
            ds = f[name]
            if ds.shape != shape:
                problems.append(f"/{name} has shape {ds.shape}, expected {shape}")
            if kind == "S":
                if ds.dtype.kind != "S":
                    problems.append(f"/{name} is {ds.dtype}, expected fixed-length strings")
            elif ds.dtype != np.dtype(kind):
                problems.append(f"/{name} is {ds.dtype}, expected {kind}")
            elif ds.dtype.kind == "f" and not np.all(np.isfinite(ds[()])):
                problems.append(f"/{name} holds NaN or inf")
        if problems:  # a layout this schema does not have: say so, read no further
            return problems, {}
        status = check_grid_status(f, n, problems)
        done = status == 1
        if np.any(f["results/FN_pre"][()][done] <= 0):
            problems.append("a done case has F_N <= 0 before the step")
        failed = status == -1
        msgs = f["results/message"][()]
        if any(len(m) == 0 for m in msgs[failed]):
            problems.append("a failed case has no message")
        if expect_failed is not None and int(np.sum(failed)) != expect_failed:
            problems.append(f"{int(np.sum(failed))} failed cases, expected {expect_failed}")
        if complete and np.any(status == 0):
            problems.append(f"{int(np.sum(status == 0))} cases are still pending")
        counts = {"cases": n, "done": int(np.sum(status == 1)), "failed": int(np.sum(status == -1)),
                  "pending": int(np.sum(status == 0))}
    return problems, counts


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("map")
    ap.add_argument("--complete", action="store_true", help="no case may be pending")
    ap.add_argument("--quiet", action="store_true")
    ap.add_argument("--expect-failed", type=int, default=None, metavar="N",
                    help="exactly N cases must be marked failed, each with a message")
    args = ap.parse_args()
    try:
        problems, counts = check(args.map, args.complete, args.expect_failed)
    except OSError as e:
        print(f"check_map: cannot read {args.map}: {e}", file=sys.stderr)
        return 1
    for p in problems:
        print(f"check_map: {args.map}: {p}", file=sys.stderr)
    if not args.quiet and counts:
        print(f"{args.map}: valid={not problems} " + " ".join(f"{k}={v}" for k, v in counts.items()))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
