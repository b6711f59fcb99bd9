"""mdrmap.simulate against `mdrmap simulate`: the same numbers bit for bit on
the history and load case sets (cases/case_set.hpp, cases/load_case_set.hpp),
the same records (events, pre, info, case); arrays without a copy;
stationary; the parameter table as the CLI's help gives it."""
import math

import numpy as np
import pytest

import mdrmap
from conftest import case_set, run_cli

SAMPLES = 21


def cli_args(kw):
    """The command line of keyword arguments: numbers as repr (the shortest
    text that reads back to the same double), the history as W:T,..."""
    args = []
    for key, value in kw.items():
        if key == "history":
            value = ",".join(f"{w!r}:{T!r}" for w, T in value)
        elif not isinstance(value, str):
            value = repr(value)
        args += ["--" + key.replace("_", "-"), value]
    return args


def parse_csv(text):
    """The CLI's output: {comment key: {field: text}}, events list, header, rows."""
    comments, events, lines = {}, [], text.splitlines()
    body = [ln for ln in lines if not ln.startswith("#")]
    for ln in lines:
        if not ln.startswith("# "):
            continue
        words = ln[2:].split()
        fields = dict(w.split("=", 1) for w in words if "=" in w)
        if words[0] == "event":
            events.append(fields)
        elif words[0] == "mdrmap":
            comments["info"] = fields
        else:
            comments[words[0]] = fields
    header = body[0].split(",")
    rows = np.array([[float(x) for x in ln.split(",")] for ln in body[1:]])
    return comments, events, header, rows


def same(a, b):
    return a == b or (math.isnan(a) and math.isnan(b))


def check_equal(exe, kw):
    r = mdrmap.simulate(**kw)
    code, out, err = run_cli(exe, cli_args(kw))
    assert code == 0, err
    comments, events, header, rows = parse_csv(out)
    assert header == ["t", "segment", "FN", "Fx", "mu", "a2"] + (["d", "a1"] if r.load else [])
    for j, name in enumerate(header):
        assert np.array_equal(getattr(r, name), rows[:, j], equal_nan=True), name
    assert r.segment.dtype == np.int32
    assert len(events) == len(r.events)
    for mine, theirs in zip(r.events, events):
        assert mine.keys() == theirs.keys()
        for key, text in theirs.items():
            if key == "D_c_undefined":  # (a word: why D_c is nan)
                assert mine[key] == text
                continue
            assert same(float(mine[key]), float(text)), key
    assert list(r.pre) == list(comments["pre"])
    for key, text in comments["pre"].items():
        assert same(r.pre[key], float(text)), key
    info = comments["info"]
    assert r.info["solver"] == info["solver"]
    for key in ("rtol", "error_estimate", "cells_per_a1"):
        assert r.info[key] == float(info[key]), key
    for key in ("elements", "steps", "element_updates", "root_solves"):
        assert r.info[key] == int(info[key]), key
    for key in ("error_vs_exact", "error_vs_reference", "reference_rtol"):
        if key in r.info or any(key in c for c in comments.values()):
            theirs = next(c[key] for c in comments.values() if key in c)
            assert r.info[key] == float(theirs), key
    case = comments["case"]
    hist = ",".join(f"{w!r}:{T!r}" for w, T in r.case["history"])
    assert [tuple(map(float, s.split(":"))) for s in case["history"].split(",")] == \
        [tuple(map(float, s.split(":"))) for s in hist.split(",")]
    for key, value in r.case.items():
        if key == "aT" and key not in case:  # the CLI shows aT only where it shifts
            assert value == 1.0
        elif key == "prony":
            assert ",".join(f"{G!r}:{t!r}" for G, t in value) == case[key] or \
                [tuple(map(float, x.split(":"))) for x in case[key].split(",")] == list(value)
        elif key not in ("history", "spacing"):
            assert value == float(case[key]), key
    assert r.case["spacing"] == case["spacing"]
    assert r.scales.keys() == comments["scales"].keys()
    for key, text in comments["scales"].items():
        assert r.scales[key] == float(text), key


@pytest.mark.parametrize("which", ["history", "load"])
def test_case_sets_equal_the_cli_bit_for_bit(exe, which):
    cases = case_set(which, SAMPLES)
    assert len(cases) >= 20
    for name, kw in cases:
        try:
            check_equal(exe, kw)
        except AssertionError as e:
            raise AssertionError(f"{which} case {name!r}: {e}") from None


@pytest.mark.parametrize("kw", [
    dict(d=0.1, R=10, tau=1, v=2, v1=0.5),  # the default window, 201 samples
    dict(d=0.1, R=10, tau=0, v=2, v1=0, samples=7),
    dict(d=0.1, R=10, tau=1, v=2, v1=0.5, t_end=3, samples=9, solver="row", rtol=1e-3),
    dict(d=0.1, R=10, tau=1, v=1, history=[(1, 2), (0, 1000), (1, 5)], samples=31,
         spacing="log", log_decades=6, G=2.5),
    dict(F0=0.1, R=10, tau=1, v=1, history=[(0.1, 20), (1, 20)], samples=11, solver="row"),
    dict(F0=0.1, R=10, tau=1, v=1, history=[(0.1, 20), (1, 20)], samples=11, solver="spectrum"),
])
def test_examples_of_the_help_equal_the_cli(exe, kw):
    check_equal(exe, kw)


def test_texts_are_taken_as_the_cli_takes_them():
    a = mdrmap.simulate(d=0.1, R=10, tau=1, v=2, v1=0.5, samples=5)
    b = mdrmap.simulate(d="0.1", R="1e1", tau="1", v="2", v1="0.5", samples="5")
    c = mdrmap.simulate(d=np.float64(0.1), R=np.int64(10), tau=1.0, v=2, history="0.5:6",
                        samples=5.0)
    for r in (b, c):
        assert np.array_equal(a.mu, r.mu) and np.array_equal(a.t, r.t)


def test_arrays_are_views_of_the_result_without_a_copy():
    r = mdrmap.simulate(F0=0.1, R=10, tau=1, v=1, v1=2, samples=11)
    for name in ("t", "segment", "FN", "Fx", "mu", "a2", "d", "a1"):
        arr = getattr(r, name)
        assert not arr.flags.owndata and arr.base is not None, name
        assert arr.shape == (11,)
    mu = r.mu
    del r  # the arrays keep the result alive
    assert np.isfinite(mu).all()
    assert not hasattr(mdrmap.simulate(d=0.1, R=10, tau=1, v=2, v1=1, samples=3), "d")


@pytest.mark.parametrize("load", [False, True])
def test_stationary_is_the_events_stationary_state(load):
    base = dict(F0=0.05, R=3, tau=2, v=0.7, G=1.5) if load else dict(d=0.02, R=3, tau=2, v=0.7)
    st = mdrmap.stationary(**base)
    r = mdrmap.simulate(**base, v1=0.07, samples=5)
    assert st["mu"] == r.events[0]["mu_ss_before"]
    assert list(st) == list(r.pre)
    assert st["mu"] == pytest.approx(r.pre["mu"], rel=1e-6)
    with pytest.raises(mdrmap.InvalidInput) as e:
        mdrmap.stationary(**base, v1=1)
    assert e.value.option == "v1"


@pytest.mark.parametrize("load", [False, True])
def test_stationary_of_each_profile(load):
    loading = dict(F0=0.05) if load else dict(d=0.02)
    par = mdrmap.stationary(**loading, R=3, tau=2, v=0.7)
    power = mdrmap.stationary(**loading, profile="power", n=2, A=1 / 6, tau=2, v=0.7)
    for key in ("FN", "Fx", "mu", "a2"):
        assert power[key] == pytest.approx(par[key], rel=1e-14, abs=0)
    # the cone on the Kelvin foundation once v tau >= a1: mu = (pi/2) tan(beta)
    cone = mdrmap.stationary(**loading, profile="cone", beta=10, tau=2, v=1e3)
    assert cone["mu"] == pytest.approx(math.pi / 2 * math.tan(math.radians(10)), rel=1e-14)
    assert cone["a2"] == 0
    for bad, option in ((dict(profile="cone", beta=10, R=3), "R"),
                        (dict(profile="cone", beta=90), "beta"),
                        (dict(profile="power", n=0.5, A=1), "n"),
                        (dict(R=3, beta=10), "beta")):
        with pytest.raises(mdrmap.InvalidInput) as e:
            mdrmap.stationary(**loading, **bad, tau=2, v=1)
        assert e.value.option == option
    with pytest.raises(mdrmap.InvalidInput) as e:
        mdrmap.simulate(**loading, profile="cone", beta=10, tau=2, v=1, v1=0.5, solver="exact")
    assert e.value.option == "profile"
    # auto takes it (the spectrum solver): a rise on the plateau, rear face
    # free, stays at mu = (pi/2) tan(beta) exactly
    r = mdrmap.simulate(**loading, profile="cone", beta=10, tau=2, v=0.2, v1=2, t_end=0.05,
                        samples=3)
    assert r.events[0]["mu_after"] == pytest.approx(cone["mu"], rel=1e-12)
    assert r.events[0]["mu_end"] == pytest.approx(cone["mu"], rel=1e-12)


def test_parameters_are_the_table_of_the_help(exe):
    table = mdrmap.parameters()
    code, out, _ = run_cli(exe, ["--help-all"])
    assert code == 0
    flat = " ".join(out.split())
    names = [p["name"] for p in table]
    assert names[:2] == ["d", "F0"] and "tau" in names and "log-decades" in names
    for p in table:
        assert " ".join(p["help"].split()) in flat, p["name"]
        assert f"--{p['name']} {p['symbol']}" in out
        assert p["keyword"] == p["name"].replace("-", "_")
        assert p["range"][1:] in p["help"] and p["meaning"] in p["help"] and p["unit"] in p["help"]
        if p["default"] is not None:
            assert not p["required"] and p["one_of"] is None
    assert {p["name"]: p["default"] for p in table}["samples"] == 201
    assert {p["name"]: p["required"] for p in table}["tau"]
    # a profile's own parameters say which (required for it alone); the rest apply to every one
    profiles = {p["name"]: p["profile"] for p in table}
    assert profiles["R"] == "parabola" and profiles["beta"] == "cone"
    assert profiles["n"] == profiles["A"] == "power" and profiles["tau"] is None


def test_info_names_the_build():
    r = mdrmap.simulate(d=0.1, R=10, tau=1, v=2, v1=0.5, samples=3)
    assert r.info["version"] == mdrmap.__version__
    assert r.info["commit"] == mdrmap._core.commit
    assert r.info["solver"] == "exact" and r.info["wall_seconds"] >= 0


def test_history_file_gives_the_records_rows_as_the_cli(exe, tmp_path):
    """A lab record: v0 and the history from its rows, a segment per velocity
    change; one sample per record row (t from the first row), with the row's
    v and slip, equal to the CLI's CSV rows bit for bit; the case says
    sampling "record"."""
    rec = tmp_path / "record.csv"
    rec.write_text("# step and hold\nmu,v,t\n0.5,1,10\n0.5,1,11\n0.5,0.5,12\n"
                   "0.5,0.5,14\n0.5,0,15\n0.5,0,17\n")
    for load in (False, True):
        kw = dict(F0=0.1) if load else dict(d=0.1)
        r = mdrmap.simulate(**kw, R=10, tau=1, history_file=rec)
        assert r.case["history"] == [(1.0, 2.0), (0.5, 3.0), (0.0, 2.0)]
        assert r.case["v"] == 1.0 and r.case["sampling"] == "record" and r.record
        assert "samples" not in r.case and "spacing" not in r.case
        assert list(r.t) == [0, 1, 2, 4, 5, 7]  # the rows' times
        assert list(r.segment) == [0, 0, 1, 1, 2, 2]
        assert list(r.v) == [1, 1, 0.5, 0.5, 0, 0] and list(r.slip) == [0, 1, 2, 3, 3.5, 3.5]
        code, out, err = run_cli(exe, [x for k, v in kw.items() for x in ("--" + k, str(v))] +
                                 ["--R", "10", "--tau", "1", "--history-file", str(rec)])
        assert code == 0, err
        _, _, header, rows = parse_csv(out)
        assert header == r.columns and len(rows) == 6
        for j, name in enumerate(header):
            assert np.array_equal(getattr(r, name), rows[:, j]), name
        assert list(r.to_dataframe().columns) == r.columns
    ref = mdrmap.simulate(d=0.1, R=10, tau=1, v=1, history=[(1, 2), (0.5, 3), (0, 2)],
                          samples=3)
    r = mdrmap.simulate(d=0.1, R=10, tau=1, history_file=rec)
    # instants both have: just after the change at t = 2, and the end at t = 7
    assert (r.t[2], r.segment[2], r.mu[2]) == (ref.t[3], ref.segment[3], ref.mu[3])
    assert (r.t[-1], r.mu[-1], r.a2[-1]) == (ref.t[-1], ref.mu[-1], ref.a2[-1])


def test_segments_and_events_are_numbered_as_the_cli_csv(exe):
    """Segment k (the k-th pair of history=, from 0) is the CSV's segment k
    and the change at its start the CSV's event k; a study config names the
    same segment k + 1 (wK, TK). The convention of docs/python.md."""
    kw = dict(d=0.1, R=10, tau=1, v=1, history=[(0.5, 1), (0, 2), (2, 1)], samples=4)
    r = mdrmap.simulate(**kw)
    code, out, err = run_cli(exe, cli_args(kw))
    assert code == 0, err
    _, events, header, rows = parse_csv(out)
    assert np.array_equal(r.segment, rows[:, header.index("segment")])
    assert sorted(set(r.segment)) == [0, 1, 2]
    assert [e["k"] for e in r.events] == [int(e["k"]) for e in events] == [0, 1, 2]
    for k, (w, T) in enumerate(kw["history"]):
        assert r.events[k]["w_after"] == w and r.events[k]["t"] == r.t[r.segment == k][0]
        assert r.t[r.segment == k][-1] - r.t[r.segment == k][0] == T
