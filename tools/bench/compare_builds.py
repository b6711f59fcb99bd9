#!/usr/bin/env python3
"""Two builds of `mdrmap` side by side on a real material over a lab test.

    python3 tools/bench/compare_builds.py OLD_MDRMAP NEW_MDRMAP [--reps N]

The scenes of mdrmap_bench_material that the CLI of any build since the
spectrum solver can run: an elastomer with 11 Prony terms G_k = 89/11 at
tau_k = 1e-9 .. 10 s (G = 1, no parallel dashpot), a sphere R = 0.05
(mm, s, MPa, N), 201 samples a segment, rtol 1e-3; the velocity-step test
--v 0.1 --history 1:5,0.1:20,1:5 under the load F0 = 0.01 and at the depth
d = 0.005, each also with every segment 10x longer, and a slide-hold-slide
test under load with a 100 s hold. Each command runs N times (default 3) for
each build, the builds alternating; the table gives the median CPU time
(user + system of the child) of each and the ratio old / new, all from this
one run. A run that fails prints its error line instead.
"""
import argparse
import resource
import statistics
import subprocess
import sys
import tempfile

TERMS = ",".join(f"{89 / 11:.6g}:1e{k}" for k in range(-9, 2))
BASE = ["--R", "0.05", "--G", "1", "--tau", "0", "--prony", TERMS, "--v", "0.1",
        "--samples", "201", "--rtol", "1e-3"]
STEPS, STEPS10 = "1:5,0.1:20,1:5", "1:50,0.1:200,1:50"
SCENES = {
    "load": ["--F0", "0.01", "--history", STEPS],
    "load, 10x": ["--F0", "0.01", "--history", STEPS10],
    "depth": ["--d", "0.005", "--history", STEPS],
    "depth, 10x": ["--d", "0.005", "--history", STEPS10],
    "SHS 100 s, load": ["--F0", "0.01", "--history", "1:5,0:100,1:5"],
}


def cpu_of(exe, args, out):
    """CPU seconds of one `exe simulate` run, or the error line it printed."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run([exe, "simulate", *BASE, *args, "--output", out],
                       capture_output=True, text=True, stdin=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        lines = p.stderr.strip().splitlines()
        return lines[-1] if lines else f"exit {p.returncode}"
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("old", help="the older build's mdrmap")
    ap.add_argument("new", help="the newer build's mdrmap")
    ap.add_argument("--reps", type=int, default=3, help="runs per build and scene (default 3)")
    a = ap.parse_args()
    if a.reps < 1:
        sys.exit("compare_builds.py: --reps: must be at least 1")
    print(f"{'scene':16s} {'old s':>8s} {'new s':>8s} {'old/new':>8s}"
          f"   (CPU, median of {a.reps}, alternating)")
    with tempfile.TemporaryDirectory() as tmp:
        out = f"{tmp}/run.csv"
        for name, args in SCENES.items():
            old, new = [], []
            for _ in range(a.reps):
                old.append(cpu_of(a.old, args, out))
                new.append(cpu_of(a.new, args, out))
            failed = [x for x in old + new if isinstance(x, str)]
            if failed:
                print(f"{name:16s} failed: {failed[0]}")
                continue
            mo, mn = statistics.median(old), statistics.median(new)
            print(f"{name:16s} {mo:8.3f} {mn:8.3f} {mo / mn:8.1f}")


if __name__ == "__main__":
    main()
