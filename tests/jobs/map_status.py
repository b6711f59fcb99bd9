# pyrun-needs: numpy h5py
"""map_status.py MAP: prints the numbers of done, pending and failed cases."""
import sys

import h5py

with h5py.File(sys.argv[1], "r") as f:
    s = f["results/status"][()]
print(int((s == 1).sum()), int((s == 0).sum()), int((s == -1).sum()))
