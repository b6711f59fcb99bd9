#!/usr/bin/env python3
# pyrun-needs: h5py numpy
"""Sets one case's status byte of a map, for the bad-input rows.

Usage: set_status.py MAP.h5 CASE VALUE   (CASE from 0; VALUE any int8, e.g.
7, which no study writes: the map is then damaged)
"""
import sys

import h5py


def main():
    path, case, value = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    with h5py.File(path, "r+") as f:
        f["results/status"][case] = value


if __name__ == "__main__":
    main()
