#!/usr/bin/env python3
"""Compare two mdrmap friction maps bit for bit.

Usage: compare_maps.py A.h5 B.h5 [--done-only]

Every dataset must be identical (NaN-aware, exact bits), except
/results/wall_seconds (timings) and the root attributes that describe the run
(created_utc, command_line, mpi_size). With --done-only, rows are compared
only where A's status is 1 (done): for a map from an interrupted run, the
finished cases must equal the reference (/failures, which lists the failed
cases of the last run, is then not compared). Reads mdrmap-map/1 and
mdrmap-map/2 maps (the fill value of undefined values compares as any other
bits). Exits 0 when equal, 1 otherwise.
"""
import argparse
import sys

import h5py
import numpy as np

SKIP_DATASETS = {"results/wall_seconds"}
SKIP_ATTRS = {"created_utc", "command_line", "mpi_size"}


def datasets(f):
    out = {}
    f.visititems(lambda name, obj: out.__setitem__(name, obj) if isinstance(obj, h5py.Dataset) else None)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--done-only", action="store_true")
    args = ap.parse_args()
    diffs = []
    with h5py.File(args.a, "r") as fa, h5py.File(args.b, "r") as fb:
        for k in sorted(set(fa.attrs) | set(fb.attrs)):
            if k in SKIP_ATTRS:
                continue
            if k not in fa.attrs or k not in fb.attrs:
                diffs.append(f"root attribute {k} only in one map")
            elif not np.array_equal(np.asarray(fa.attrs[k]), np.asarray(fb.attrs[k])):
                diffs.append(f"root attribute {k} differs")
        da, db = datasets(fa), datasets(fb)
        if set(da) != set(db):
            diffs.append(f"datasets differ: {sorted(set(da) ^ set(db))}")
        rows = None
        if args.done_only:
            rows = fa["results/status"][()] == 1
        for name in sorted(set(da) & set(db)):
            if name in SKIP_DATASETS or (rows is not None and name.startswith("failures/")):
                continue
            x, y = da[name][()], db[name][()]
            if x.shape != y.shape or x.dtype != y.dtype:
                diffs.append(f"/{name}: shape/type {x.shape} {x.dtype} vs {y.shape} {y.dtype}")
                continue
            if rows is not None and x.ndim >= 1 and x.shape[0] == rows.shape[0] and \
                    name.split("/")[0] in ("results", "events", "analytic", "residuals", "scales",
                                        "timeseries"):
                x, y = x[rows], y[rows]
            if x.dtype.kind == "f":
                same = np.array_equal(x.view(np.uint64 if x.dtype.itemsize == 8 else np.uint32),
                                      y.view(np.uint64 if y.dtype.itemsize == 8 else np.uint32))
            else:
                same = np.array_equal(x, y)
            if not same:
                diffs.append(f"/{name} differs")
    for d in diffs:
        print(f"compare_maps: {d}", file=sys.stderr)
    if not diffs:
        print(f"compare_maps: {args.a} and {args.b} are identical" +
              (" on the done rows" if args.done_only else ""))
    return 1 if diffs else 0


if __name__ == "__main__":
    sys.exit(main())
