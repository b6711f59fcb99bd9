"""Numbers stay numbers (issue 34): a Python number reaches the core as that
double, never through a text; a text is still read as the command line reads
it; a value of the wrong type (a bool, bytes, a path where a number is
expected) is refused naming the keyword, as an InvalidInput that is also a
TypeError."""
import pathlib
import struct

import numpy as np
import pytest

import mdrmap
from conftest import run_cli
from test_simulate import check_equal, parse_csv


def bits(x):
    return struct.pack("<d", float(x))


def test_full_precision_numbers_reach_the_core_bit_for_bit(exe):
    """Doubles of 17 significant digits (no short text reads back to them),
    given as floats, make the case the command line makes of their %.17g
    texts, and the same results bit for bit."""
    rng = np.random.default_rng(34)
    for _ in range(3):
        d, R, tau, v, w1, w2 = rng.uniform([0.05, 5, 0.5, 1, 0.1, 1], [0.2, 20, 2, 3, 0.9, 3])
        kw = dict(d=float(d), R=float(R), tau=float(tau), v=float(v), samples=9,
                  history=[(float(w1), 1.3 * float(tau)), (float(w2), 0.7)])
        r = mdrmap.simulate(**kw)
        for key in ("d", "R", "tau", "v"):
            assert bits(r.case[key]) == bits(kw[key]), key
        assert [tuple(map(bits, s)) for s in r.case["history"]] == \
            [tuple(map(bits, s)) for s in kw["history"]]
        args = [x for k in ("d", "R", "tau", "v") for x in ("--" + k, "%.17g" % kw[k])]
        args += ["--samples", "9", "--history",
                 ",".join("%.17g:%.17g" % s for s in kw["history"])]
        code, out, err = run_cli(exe, args)
        assert code == 0, err
        _, _, header, rows = parse_csv(out)
        for j, name in enumerate(header):
            assert [bits(x) for x in getattr(r, name)] == [bits(x) for x in rows[:, j]], name
        check_equal(exe, kw)  # (repr texts: the records too)


def test_numpy_scalars_and_large_ints_are_their_values():
    x32 = np.float32(0.1)  # not 0.1: the float32 nearest it, widened exactly
    r = mdrmap.simulate(d=x32, R=np.int64(10), tau=np.float64(1), v=2, v1=0.5,
                        samples=np.int32(5))
    assert r.case["d"] == float(x32) != 0.1 and r.case["samples"] == 5
    big = 2**60 + 1  # above 2^53: rounded once, as strtod rounds its digits
    s = mdrmap.stationary(d=0.1, R=big, tau=1, v=2)
    assert s == mdrmap.stationary(d=0.1, R=str(big), tau=1, v=2)
    with pytest.raises(mdrmap.InvalidInput, match=r"^R: must be a finite number, got 1{400} "):
        mdrmap.simulate(d=0.1, R=int("1" * 400), tau=1, v=2, v1=0.5)


def test_pairs_triples_and_lists_are_numbers():
    a = mdrmap.simulate(d=0.1, R=10, tau=1, G=1, v=1, prony=[(np.float64(1), 0.1), (2, 10)],
                        history=[(np.float32(0.5), 2), (0, 3)], samples=5,
                        temperature=np.float64(310), wlf=(8.86, np.float64(101.6), 298))
    b = mdrmap.simulate(d="0.1", R="10", tau="1", G="1", v="1", prony="1:0.1,2:10",
                        history="%r:2,0:3" % float(np.float32(0.5)), samples="5",
                        temperature="310", wlf="8.86:101.6:298")
    assert np.array_equal(a.mu, b.mu) and a.case == b.case
    vs = np.array([0.1, 1.0, 10.0])
    many = mdrmap.stationary(d=0.1, R=10, tau=1, v=vs)
    assert [bits(x) for x in many["v"]] == [bits(x) for x in vs]


BASE = dict(d=0.1, R=10, tau=1, v=2, v1=0.5)


@pytest.mark.parametrize("change, keyword, said", [
    ({"d": np.bool_(True)}, "d", "must be a number, got True"),
    ({"d": True}, "d", "must be a number, got True"),
    ({"tau": b"1"}, "tau", "must be a number, got bytes b'1'"),
    ({"R": pathlib.Path("10")}, "R", "must be a number, got a path '10'"),
    ({"v": [2]}, "v", "must be a number, got list [2]"),
    ({"v": {"a": 1}}, "v", "must be a number, got dict"),
    ({"samples": np.bool_(False)}, "samples", "must be a number, got False"),
    ({"rtol": b"1e-3"}, "rtol", "must be a number, got bytes"),
    ({"t_end": pathlib.Path("3")}, "t_end", "must be a number, got a path"),
    ({"v1": None, "history": [(True, 1)]}, "history", "must be a number, got True"),
    ({"v1": None, "history": [(1, b"2")]}, "history", "must be a number, got bytes"),
    ({"G": 1, "prony": [(1, np.bool_(True))]}, "prony", "must be a number, got True"),
    ({"profile": 3}, "profile", "must be a str, got int 3"),
    ({"spacing": b"log"}, "spacing", "must be a str, got bytes"),
    ({"G": 1, "prony_file": 5}, "prony_file", "must be a path (a str or a pathlib.Path)"),
    ({"temperature": b"25", "wlf": (8.86, 101.6, 298)}, "temperature",
     "must be a number, got bytes"),
    ({"temperature": 310, "wlf": (8.86, True, 298)}, "wlf", "must be a number, got True"),
    ({"temperature": 310, "wlf": (8.86, 101.6, 298), "allow_large_shift": 1},
     "allow_large_shift", "must be True or False (a flag), got 1"),
], ids=lambda x: str(x)[:40])
def test_a_value_of_the_wrong_type_is_a_type_error_naming_the_keyword(change, keyword, said,
                                                                       capfd):
    kw = dict(BASE, **change)
    kw = {k: v for k, v in kw.items() if v is not None}
    with pytest.raises(TypeError) as e:
        mdrmap.simulate(**kw)
    assert isinstance(e.value, mdrmap.InvalidInput) and isinstance(e.value, ValueError)
    assert e.value.keyword == keyword and said in e.value.message, e.value.message
    assert str(e.value).startswith(keyword + ": ")
    assert capfd.readouterr() == ("", "")


@pytest.mark.parametrize("kw, args", [
    (dict(history=[(1, -2)]), ["--history", "1:-2"]),
    (dict(history=[(1, 2), (float("nan"), 1)]), ["--history", "1:2,nan:1"]),
    (dict(history=[(1, 1)] * 10001), ["--history", ",".join(["1:1"] * 10001)]),
    (dict(v1=0.5, G=1, prony=[(0, 1)]), ["--v1", "0.5", "--G", "1", "--prony", "0:1"]),
    (dict(v1=0.5, G=1, prony=[(1, 1), (2, float("inf"))]),
     ["--v1", "0.5", "--G", "1", "--prony", "1:1,2:inf"]),
    (dict(v1=0.5, G=1, prony=[(1, 2)] * 33), ["--v1", "0.5", "--G", "1", "--prony",
                                               ",".join(["1:2"] * 33)]),
    (dict(v1=0.5, temperature=20, wlf=(0, 51.6, 0)), ["--v1", "0.5", "--T", "20", "--wlf",
                                                     "0:51.6:0"]),
    (dict(v1=0.5, temperature=20, wlf=(17.44, -51.6, 0)),
     ["--v1", "0.5", "--T", "20", "--wlf", "17.44:-51.6:0"]),
    (dict(v1=0.5, temperature=-60, wlf=(17.44, 51.6, 0)),
     ["--v1", "0.5", "--T", "-60", "--wlf", "17.44:51.6:0"]),
    (dict(v1=0.5, samples=2.5), ["--v1", "0.5", "--samples", "2.5"]),
    (dict(v1=0.5, rtol=0.2), ["--v1", "0.5", "--rtol", "0.2"]),
    (dict(v1=0.5, nu=0.7, G=1, prony_file="x.csv"), None),
], ids=lambda x: str(x)[:40])
def test_typed_values_are_refused_with_the_cli_message(exe, kw, args):
    base = dict(d=0.1, R=10, tau=1, v=2)
    with pytest.raises(mdrmap.InvalidInput) as e:
        mdrmap.simulate(**base, **kw)
    if args is None:  # (nu is checked before the file is read)
        assert e.value.option == "nu" and e.value.message.endswith("got 0.7")
        return
    code, out, err = run_cli(exe, [x for k, v in base.items() for x in ("--" + k, str(v))] + args)
    assert code == 2 and out == ""
    assert err.rstrip("\n") == f"mdrmap simulate: error: --{e.value.option}: {e.value.message}"
