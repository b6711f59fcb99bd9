#!/usr/bin/env python3
"""Make damaged and foreign copies of a map, for the --resume refusal tests.

Usage: damage_map.py MAP.h5 OUTDIR

Writes into OUTDIR one file per kind of damage (the name says which) and
prints their names. The original is only read.
"""
import os
import shutil
import sys

import h5py
import numpy as np


def copy(src, outdir, name):
    dst = os.path.join(outdir, name)
    shutil.copyfile(src, dst)
    return dst


def main():
    src, outdir = sys.argv[1], sys.argv[2]
    os.makedirs(outdir, exist_ok=True)
    made = []
    size = os.path.getsize(src)

    # bytes: truncated in the middle of the raw data; superblock signature gone
    dst = copy(src, outdir, "truncated.h5")
    with open(dst, "r+b") as f:
        f.truncate(size // 2)
    made.append(dst)
    dst = copy(src, outdir, "no_signature.h5")
    with open(dst, "r+b") as f:
        f.write(b"\0" * 8)
    made.append(dst)
    dst = os.path.join(outdir, "empty.h5")
    open(dst, "wb").close()
    made.append(dst)

    # a foreign HDF5 file, and a map of another schema
    dst = os.path.join(outdir, "foreign.h5")
    with h5py.File(dst, "w") as f:
        f["results/status"] = np.zeros(10, dtype="i1")
    made.append(dst)
    dst = copy(src, outdir, "other_schema.h5")
    with h5py.File(dst, "r+") as f:
        f.attrs["mdrmap_schema"] = np.bytes_("mdrmap-map/0")
    made.append(dst)
    dst = copy(src, outdir, "schema_1.h5")  # a map of the previous schema: not continued
    with h5py.File(dst, "r+") as f:
        f.attrs["mdrmap_schema"] = np.bytes_("mdrmap-map/1")
    made.append(dst)

    # structure: a dataset missing, re-stored chunked, of the wrong shape or type
    dst = copy(src, outdir, "missing_status.h5")
    with h5py.File(dst, "r+") as f:
        del f["results/status"]
    made.append(dst)
    dst = copy(src, outdir, "chunked_field.h5")
    with h5py.File(dst, "r+") as f:
        data = f["results/FN_pre"][...]
        del f["results/FN_pre"]
        f.create_dataset("results/FN_pre", data=data, chunks=True)
    made.append(dst)
    dst = copy(src, outdir, "short_field.h5")
    with h5py.File(dst, "r+") as f:
        data = f["events/mu_end"][...]
        del f["events/mu_end"]
        f.create_dataset("events/mu_end", data=data[:-1])
    made.append(dst)
    dst = copy(src, outdir, "float32_field.h5")
    with h5py.File(dst, "r+") as f:
        data = f["residuals/a2_pre"][...]
        del f["residuals/a2_pre"]
        f.create_dataset("residuals/a2_pre", data=data.astype("f4"))
    made.append(dst)
    dst = copy(src, outdir, "no_study.h5")
    with h5py.File(dst, "r+") as f:
        del f["provenance/config_canonical"]
    made.append(dst)
    for m in made:
        print(m)


if __name__ == "__main__":
    main()
