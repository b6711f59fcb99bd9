#!/usr/bin/env bash
# long_history.sh ... NP: a grid study whose history has 10000 segments, the
# documented limit (issue 23, class 6): its 20000 history axes (w1_over_v,
# T1_over_tau, ...) are axes of the grid, described in /grid's attributes
# `axes`, `shape` and `log` (far beyond an object header's 64 KiB: dense
# attribute storage). The map is created and completed (2 cases, 2 samples per
# segment), check_map.py finds it complete, and the tools read /grid:
# python -m mdrmap mapxr opens the map with every axis (to_grid makes it 1-D over v:
# the axes of one value are scalar coordinates), python -m mdrmap map_summary summarises it.
source "$(dirname "$0")/common.sh"
np=$1
dir="$WORKDIR/long_history"
rm -rf "$dir"
mkdir -p "$dir"
K=10000
{
  printf '[grid]\nd = 1e-3\nR = 1\ntau = 1\nv = 1, 2\n[history]\n'
  for ((k = 1; k <= K; k++)); do
    printf 'w%d_over_v = %s\nT%d_over_tau = 0.01\n' "$k" "$((k % 2 ? 1 : 0))" "$k"
  done
  printf '[run]\nsamples = 2\nsolver = auto\nrtol = 1e-2\n'
} >"$dir/long.ini"
out="$dir/long.h5"
code=0
"$MPIEXEC" -np "$np" "$MDRMAP" study --quiet --config "$dir/long.ini" --output "$out" \
  2>"$dir/study.err" || code=$?
[[ $code == 0 ]] || fail "a $K-segment grid: exit $code: $(cat "$dir/study.err")"
"${CHECK[@]}" --complete "$out" || fail "the $K-segment map is not complete"
cat >"$dir/read.py" <<'PY'
# pyrun-needs: numpy h5py xarray h5netcdf
"""read.py TOOLS MAP K: /grid describes every axis; mapxr opens the map."""
import sys

import h5py

from mdrmap.tools import mapxr  # (sys.argv[1]: the source tree's tools/, unused)

path, K = sys.argv[2], int(sys.argv[3])
axes = ["d", "R", "tau", "G", "v"] + [f"{x}{k}_over_{r}" for k in range(1, K + 1)
                                      for x, r in (("w", "v"), ("T", "tau"))]
with h5py.File(path, "r") as f:
    g = f["grid"]
    have = g.attrs["axes"]
    have = (have.decode() if isinstance(have, bytes) else str(have)).split(",")
    if have != axes:
        sys.exit(f"read: /grid axes: {len(have)} of them, {have[:8]}..., expected {len(axes)}")
    if list(g.attrs["shape"]) != [1, 1, 1, 1, 2] + [1] * (2 * K):
        sys.exit("read: /grid shape is wrong")
    if f["cases/w"].shape != (2, K) or f["events/mu_end"].shape != (2, K):
        sys.exit(f"read: /cases/w {f['cases/w'].shape}, /events/mu_end {f['events/mu_end'].shape}")
ds = mapxr.open_map(path)
if dict(ds.sizes) != {"case": 2, "event": K} or ds.attrs["grid_axes"] != ",".join(axes):
    sys.exit(f"read: open_map: {dict(ds.sizes)}")
# every axis but v has one value: a scalar coordinate, so the grid is 1-D over v
g = mapxr.to_grid(ds)
if dict(g.sizes) != {"v": 2, "event": K} or g["mu_end"].dims != ("v", "event"):
    sys.exit(f"read: to_grid: {dict(g.sizes)}, expected v: 2, event: {K}")
if g["T9999_over_tau"].ndim != 0 or float(g["T9999_over_tau"]) != 0.01:
    sys.exit("read: to_grid: T9999_over_tau is not the scalar coordinate 0.01")
print(f"to_grid: {dict(g.sizes)}, {len(axes) - 1} axes of one value as scalar coordinates")
print(f"/grid: {len(axes)} axes; open_map: {dict(ds.sizes)}")
PY
"$PYRUN" "$dir/read.py" "$SRCDIR/tools" "$out" "$K" || fail "reading the $K-segment map"
"$PYRUN" -m mdrmap map_summary "$out" --no-config >"$dir/summary.txt" ||
  fail "map_summary on the $K-segment map"
grep -q "grid: $((2 * K + 5)) axes" "$dir/summary.txt" || fail "map_summary: $(head -20 "$dir/summary.txt")"
echo "PASS: a $K-segment grid: map created and complete ($(du -h "$out" | cut -f1)), tools read it"
