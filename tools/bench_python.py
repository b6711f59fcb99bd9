#!/usr/bin/env python3
# pyrun-needs: mdrmap numpy
"""Measures the Python module: the overhead of mdrmap.simulate over the core's
own time, and the speed-up of a thread pool over load-controlled cases.

  1. overhead: a fixed-depth step with 201 samples (the exact solver), called
     --calls times; per call: the whole call, the solver's own time (info
     wall_seconds, as the CLI's header gives it) and their difference; also
     the extension's call alone (_core.simulate on prepared values).
  2. threads: --cases load-controlled steps (F0, v and the step spread over
     decades), run by a ThreadPoolExecutor of 1 and of --threads workers;
     prints both wall times, the speed-up, the process's CPU time over the
     wall time (how many cores it kept busy) and the load average.

Usage:
    BUILD_DIR=build tools/pyrun tools/bench_python.py [--calls 2000] [--cases 200]
"""
import argparse
import os
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import mdrmap

STEP = dict(d=0.1, R=10, tau=1, v=2, v1=0.5, samples=201)


def overhead(calls):
    for _ in range(50):  # warm up
        mdrmap.simulate(**STEP)
    walls = []
    start = time.perf_counter()
    for _ in range(calls):
        walls.append(mdrmap.simulate(**STEP).info["wall_seconds"])
    total = (time.perf_counter() - start) / calls
    values = mdrmap._values.values(STEP, mdrmap._SIMULATE_KEYWORDS, "simulate")  # floats
    start = time.perf_counter()
    for _ in range(calls):
        mdrmap._core.simulate(values)
    ext = (time.perf_counter() - start) / calls
    core = float(np.mean(walls))
    print(f"overhead: fixed-depth step, 201 samples, {calls} calls")
    print(f"  per call {total * 1e6:.1f} us, solver (wall_seconds) {core * 1e6:.1f} us, "
          f"overhead {(total - core) * 1e6:.1f} us (the extension's call alone "
          f"{(ext - core) * 1e6:.1f} us over the solver)")


def load_cases(n):
    rng = np.random.default_rng(7)
    cases = []
    for _ in range(n):
        F0 = 10 ** rng.uniform(-4, -2)
        v = 10 ** rng.uniform(-2.5, 0)  # zeta0 = v tau / a0 from about 0.03 to 40 (tau = 1)
        w = v * 10 ** rng.choice([-1.0, 1.0])
        cases.append(dict(F0=F0, R=1, tau=1, v=v, history=[(w, 5.0)], samples=101))
    return cases


def threads(n, workers):
    cases = load_cases(n)
    times, cpu, results = {}, {}, {}
    for k in (1, workers):
        with ThreadPoolExecutor(max_workers=k) as pool:
            start, start_cpu = time.perf_counter(), time.process_time()
            results[k] = list(pool.map(lambda kw: mdrmap.simulate(**kw), cases))
            times[k] = time.perf_counter() - start
            cpu[k] = time.process_time() - start_cpu
    same = all(np.array_equal(a.mu, b.mu) for a, b in zip(results[1], results[workers]))
    load = os.getloadavg()
    print(f"threads: {n} load-controlled steps ({results[1][0].info['solver']} solver)")
    print(f"  1 thread {times[1]:.3f} s, {workers} threads {times[workers]:.3f} s, speed-up "
          f"{times[1] / times[workers]:.2f}x; results equal: {same}")
    print(f"  CPU time {cpu[1]:.3f} s and {cpu[workers]:.3f} s; CPU time / wall time: 1 thread "
          f"{cpu[1] / times[1]:.2f}, {workers} threads {cpu[workers] / times[workers]:.2f} "
          f"(cores busy at once); cores {os.cpu_count()}, "
          f"load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--calls", type=int, default=2000)
    p.add_argument("--cases", type=int, default=200)
    p.add_argument("--threads", type=int, default=2)
    a = p.parse_args()
    overhead(a.calls)
    threads(a.cases, a.threads)


if __name__ == "__main__":
    main()
