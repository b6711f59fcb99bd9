"""Ctrl-C during a call: SIGINT raises KeyboardInterrupt in the calling
(main) thread soon after it arrives, the solver stops, nothing is lost and
the next call works (src/python/call.hpp)."""
import os
import queue
import signal
import subprocess
import sys
import threading
import time

# A call of several seconds at least (a spectrum of seven terms under load,
# ten segments: about 10 s on an idle core, then its work budget ends it).
CHILD = r"""
import sys, time, mdrmap
kw = dict(F0=0.1, R=10, tau=1, G=1, v=2, history=[(0.5, 20), (2, 20)] * 5,
          prony=[(1.0, 10.0 ** k) for k in range(-3, 4)], rtol=1e-5)
def progress(f):
    print("progress", f, flush=True)
start = time.perf_counter()
try:
    mdrmap.simulate(progress=progress, **kw)
    print("returned", time.perf_counter() - start, flush=True)
except KeyboardInterrupt:
    print("interrupted", time.perf_counter() - start, flush=True)
r = mdrmap.simulate(d=0.1, R=10, tau=1, v=2, v1=0.5)
print("next", r.mu.size, flush=True)
"""


def lines_of(p):
    """The child's stdout lines as they come, on a queue (None at its end)."""
    q = queue.Queue()

    def pump():
        for line in p.stdout:
            q.put(line.strip())
        q.put(None)

    threading.Thread(target=pump, daemon=True).start()
    return q


def next_line(q, timeout):
    try:
        return q.get(timeout=timeout)
    except queue.Empty:
        return None


def test_ctrl_c_raises_keyboard_interrupt_soon_and_the_next_call_works():
    p = subprocess.Popen([sys.executable, "-c", CHILD], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, env=os.environ)
    try:
        q = lines_of(p)
        first = next_line(q, 120)  # the call runs: its first progress report
        assert first is not None and first.startswith("progress"), first
        sent = time.perf_counter()
        p.send_signal(signal.SIGINT)
        line = next_line(q, 60)
        while line is not None and line.startswith("progress"):
            line = next_line(q, 60)
        delay = time.perf_counter() - sent
        assert line is not None and line.startswith("interrupted"), \
            f"{line!r} {delay:.2f} s after SIGINT"
        print(f"KeyboardInterrupt {delay:.3f} s after SIGINT")
        assert delay < 5.0, f"KeyboardInterrupt {delay:.2f} s after SIGINT"
        assert (next_line(q, 120) or "").startswith("next ")
        assert p.wait(60) == 0
        assert p.stderr.read() == ""  # no traceback, no "lost sys.stderr"
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()
