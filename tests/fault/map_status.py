#!/usr/bin/env python3
"""Print the case counts of a map: done=N failed=N pending=N (reads only)."""
import sys

import h5py
import numpy as np

with h5py.File(sys.argv[1], "r") as f:
    st = f["results/status"][...]
print(f"done={int(np.sum(st == 1))} failed={int(np.sum(st == -1))} pending={int(np.sum(st == 0))}")
