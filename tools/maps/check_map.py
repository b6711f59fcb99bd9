#!/usr/bin/env python3
"""Check that an mdrmap friction map has the documented layout.

Usage: check_map.py MAP.h5 [--complete] [--expect-failed N] [--quiet]

Checks every dataset of schema mdrmap-map/1 (names, shapes, types), the root
provenance attributes, that status holds only -1/0/1, that no value is NaN or
infinite, and that done cases carry a positive normal force. With --complete,
also that no case is pending. Exits 0 when the map is valid, 1 otherwise,
printing one line per problem.
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


def check(path, complete, expect_failed=None):
    problems = []
    with h5py.File(path, "r") as f:
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
        if "grid" in f:
            g = f["grid"]
            axes = g.attrs["axes"]
            axes = (axes.decode() if isinstance(axes, bytes) else str(axes)).split(",")
            shape = tuple(int(x) for x in g.attrs["shape"])
            if int(np.prod(shape)) != n:
                problems.append(f"grid shape {shape} does not multiply to {n} cases")
            for a, k in zip(axes, shape):
                if a not in g or g[a].shape != (k,):
                    problems.append(f"/grid/{a} missing or not of length {k}")
        status = f["results/status"][()]
        bad = set(np.unique(status)) - {-1, 0, 1}
        if bad:
            problems.append(f"status holds values {sorted(bad)}")
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
