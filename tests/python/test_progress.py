"""progress=: a callable the calling thread calls with the fraction of the
samples done (RunControl::report), at most about every 0.2 s, and with 1.0
when the call succeeded; an exception it raises stops the call."""
import threading

import numpy as np
import pytest

import mdrmap

# about 2 s on an idle core: a spectrum of seven terms under load
LONG = dict(F0=0.1, R=10, tau=1, G=1, v=2, history=[(0.5, 20), (2, 20)],
            prony=[(1.0, 10.0 ** k) for k in range(-3, 4)], rtol=1e-5)


def test_progress_reports_fractions_from_the_calling_thread():
    calls = []
    r = mdrmap.simulate(progress=lambda f: calls.append((f, threading.get_ident())), **LONG)
    fractions = [f for f, _ in calls]
    assert fractions[-1] == 1.0
    assert all(0.0 <= f <= 1.0 for f in fractions)
    assert any(0.0 < f < 1.0 for f in fractions), fractions  # reports while it runs
    assert {ident for _, ident in calls} == {threading.get_ident()}
    assert r.t.size == 2 * 201


def test_progress_leaves_the_numbers_alone():
    kw = dict(F0=0.1, R=10, tau=1, v=1, history=[(0.1, 20), (1, 20)], samples=101)
    calls = []
    r, plain = mdrmap.simulate(progress=calls.append, **kw), mdrmap.simulate(**kw)
    assert calls[-1] == 1.0
    for name in ("t", "FN", "Fx", "mu", "a2", "d", "a1"):
        assert np.array_equal(getattr(r, name), getattr(plain, name))


def test_an_exception_of_the_callback_stops_the_call():
    class Enough(Exception):
        pass

    def stop(f):
        raise Enough(f)

    with pytest.raises(Enough):
        mdrmap.simulate(progress=stop, **LONG)
    assert mdrmap.simulate(d=0.1, R=10, tau=1, v=2, v1=0.5).t.size == 201


def test_stationary_reports_progress_over_its_velocities():
    fractions = []
    out = mdrmap.stationary(d=0.1, R=10, tau=1, v=[0.1, 1, 10], progress=fractions.append)
    assert fractions[-1] == 1.0 and out["mu"].shape == (3,)


def test_progress_must_be_callable():
    with pytest.raises(TypeError, match="progress must be a callable"):
        mdrmap.simulate(d=0.1, R=10, tau=1, v=2, v1=0.5, progress=0.5)
