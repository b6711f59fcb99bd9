"""Threads: the solver runs without the GIL, so cases run concurrently in a
thread pool, with the same results as one after another."""
import threading
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import mdrmap
from conftest import case_set


def load_cases():
    return [kw for _, kw in case_set("load", 11)]


def test_a_thread_pool_gives_the_serial_results():
    cases = [kw for kw in load_cases() if "zeta0=1e6" not in str(kw)][:24]
    cases += [kw for _, kw in case_set("history", 11)]
    serial = [mdrmap.simulate(**kw) for kw in cases]
    with ThreadPoolExecutor(max_workers=4) as pool:
        parallel = list(pool.map(lambda kw: mdrmap.simulate(**kw), cases))
    for a, b in zip(serial, parallel):
        for name in ("t", "FN", "Fx", "mu", "a2"):
            assert np.array_equal(getattr(a, name), getattr(b, name), equal_nan=True)
        assert a.events == b.events or str(a.events) == str(b.events)  # nan != nan


def test_other_threads_run_while_the_solver_runs():
    # a case of a few tenths of a second (the load solver, zeta0 = 1e6 and a
    # drop by 1e-6): while it runs, this thread (pure Python, it needs the GIL)
    # keeps ticking; were the GIL held through the solver, no tick could fall
    # inside the call's middle
    kw = dict(F0=0.004, R=2, tau=1, v=114471.4242553332, samples=11,
              history=[(0.1144714242553332, 3.0), (114.4714242553332, 2.0)])
    times = {}

    def work():
        times["start"] = time.perf_counter()
        times["result"] = mdrmap.simulate(**kw)
        times["end"] = time.perf_counter()

    ticks = []
    th = threading.Thread(target=work)
    th.start()
    deadline = time.perf_counter() + 600
    while th.is_alive() and time.perf_counter() < deadline:
        ticks.append(time.perf_counter())
        time.sleep(0.0005)
    th.join()
    start, end = times["start"], times["end"]
    assert end - start > 0.02, "the case ran too briefly to tell"
    middle = [t for t in ticks if start + 0.3 * (end - start) < t < end - 0.3 * (end - start)]
    assert len(middle) >= 3, f"{len(middle)} ticks in the middle of a {end - start:.3f} s call"


def test_other_threads_run_while_the_main_thread_calls_and_polls():
    # the call in the main thread looks at signals and progress every 20 ms
    # (it takes the GIL for that): between two looks it must not hold the GIL,
    # so a pure-Python counter thread keeps ticking through the call's middle
    kw = dict(F0=0.004, R=2, tau=1, v=114471.4242553332, samples=11,
              history=[(0.1144714242553332, 3.0), (114.4714242553332, 2.0)])
    done = threading.Event()
    ticks = []

    def count():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.0005)

    th = threading.Thread(target=count)
    th.start()
    try:
        start = time.perf_counter()
        mdrmap.simulate(progress=lambda f: None, **kw)
        end = time.perf_counter()
    finally:
        done.set()
        th.join()
    assert end - start > 0.02, "the case ran too briefly to tell"
    middle = [t for t in ticks if start + 0.3 * (end - start) < t < end - 0.3 * (end - start)]
    assert len(middle) >= 3, f"{len(middle)} ticks in the middle of a {end - start:.3f} s call"
