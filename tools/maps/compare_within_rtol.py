#!/usr/bin/env python3
"""Compare two friction maps of one study case by case, within rtol.

    python3 tools/maps/compare_within_rtol.py OLD.h5 NEW.h5 --rtol E

Both maps must hold the same cases (the same /cases columns, in the same
order) and their timeseries (study option --timeseries true). Per case, as
the error metric measures a run against its reference (docs/design/
accuracy.md): for each series q of FN, Fx, mu (and d under load), the largest
|q_new - q_old| over the samples divided by the largest |q_old|; for a2 (and
a1) divided by the largest a1 (the leading edge; at fixed depth the contact
radius of /cases). A series that is zero in the old map (Fx and mu of a
purely elastic case) is measured on 1e-12 of its partner's scale. Prints the
largest difference over rtol and where; exit 0 when every case is within
rtol, 1 when one is not, 2 on bad input.
"""
import argparse
import sys

import h5py
import numpy as np


def series(f, name):
    ds = f.get("timeseries/" + name)
    return None if ds is None else np.asarray(ds[...], dtype=float)


def scale_rows(x):
    return np.max(np.abs(x), axis=1)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("old")
    p.add_argument("new")
    p.add_argument("--rtol", type=float, required=True)
    a = p.parse_args()
    with h5py.File(a.old, "r") as fo, h5py.File(a.new, "r") as fn:
        if "timeseries/mu" not in fo or "timeseries/mu" not in fn:
            sys.exit("compare_within_rtol: both maps need their timeseries (--timeseries true)")
        done = (np.asarray(fo["results/status"]) == 1) & (np.asarray(fn["results/status"]) == 1)
        for col in fo["cases"]:
            if col in fn["cases"] and not np.array_equal(
                    np.asarray(fo["cases"][col]), np.asarray(fn["cases"][col]), equal_nan=True):
                sys.exit(f"compare_within_rtol: the maps differ in /cases/{col}")
        t_old, t_new = series(fo, "t"), series(fn, "t")
        if t_old.shape != t_new.shape or not np.allclose(t_old, t_new, rtol=1e-12, atol=0):
            sys.exit("compare_within_rtol: the maps' output instants differ")
        a1 = series(fo, "a1")
        if a1 is None:
            a1 = np.repeat(scale_rows(series(fo, "a2"))[:, None], t_old.shape[1], axis=1)
        worst, where = 0.0, ""
        for name in ("FN", "Fx", "mu", "d", "a2", "a1"):
            o, n = series(fo, name), series(fn, name)
            if o is None or n is None:
                continue
            ref = scale_rows(a1) if name in ("a2", "a1") else scale_rows(o)
            floor = 1e-12 * np.maximum(scale_rows(n), 1e-300)
            err = scale_rows(n - o) / np.maximum(ref, floor) / a.rtol
            err[~done] = 0.0
            k = int(np.argmax(err))
            if err[k] > worst:
                worst, where = float(err[k]), f"{name} of case {k}"
        print(f"{int(done.sum())} cases: largest difference {worst:.3g} rtol ({where or '-'})")
        return 0 if worst <= 1.0 else 1


if __name__ == "__main__":
    sys.exit(main())
