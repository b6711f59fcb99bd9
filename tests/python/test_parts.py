"""The parts of a case as objects (issue 34): mdrmap.Material, mdrmap.Indenter
and mdrmap.History check their values when made, with the messages of
mdrmap.simulate (the command line's), show themselves as the call that makes
them, and give mdrmap.simulate / mdrmap.stationary the same case (and the
same results, bit for bit) as the keywords they stand for."""
import numpy as np
import pytest

import mdrmap

SPECTRUM = [(1.0, 0.1), (2.0, 10.0)]


def same_run(a, b):
    assert a.case == b.case
    for name in a.columns:
        assert np.array_equal(getattr(a, name), getattr(b, name), equal_nan=True), name


def test_objects_give_the_case_of_their_keywords():
    m = mdrmap.Material(G=1, prony=SPECTRUM, aT=0.5)
    i = mdrmap.Indenter("cone", beta=10)
    h = mdrmap.History([(0.1, 2), (0, 5), (1, 2)])
    a = mdrmap.simulate(material=m, indenter=i, history=h, F0=0.1, v=1, samples=7)
    b = mdrmap.simulate(G=1, tau=0, prony=SPECTRUM, aT=0.5, profile="cone", beta=10,
                        history=[(0.1, 2), (0, 5), (1, 2)], F0=0.1, v=1, samples=7)
    same_run(a, b)
    kelvin, parabola = mdrmap.Material(G=2, tau=1), mdrmap.Indenter(R=10)
    s = mdrmap.stationary(material=kelvin, indenter=parabola, d=0.1, v=[0.5, 2])
    t = mdrmap.stationary(G=2, tau=1, R=10, d=0.1, v=[0.5, 2])
    assert all(np.array_equal(s[k], t[k]) for k in t)


def test_attributes_are_what_the_core_read():
    m = mdrmap.Material(G=1, tau=0.5, temperature="35C", wlf=(8.86, 101.6, "25C"))
    assert (m.G, m.tau, m.prony) == (1.0, 0.5, [])
    assert m.temperature == 35.0 and m.unit == "C" and m.wlf == (8.86, 101.6, 25.0)
    r = mdrmap.simulate(material=m, R=10, d=0.1, v=1, v1=2, samples=3)
    assert r.case["aT"] == m.aT < 1
    assert mdrmap.Material(G=1, prony=SPECTRUM).tau == 0.0  # a spectrum: no dashpot
    i = mdrmap.Indenter("power", n=3, A=0.5)
    assert (i.profile, i.n, i.A) == ("power", 3.0, 0.5)
    h = mdrmap.History(np.array([[1, 2], [0, 3]]))
    assert h.segments == [(1.0, 2.0), (0.0, 3.0)] and len(h) == 2 and h.v is None


@pytest.mark.parametrize("obj", [
    mdrmap.Material(G=2, tau=1),
    mdrmap.Material(G=1, tau=0.0, prony=[(1, 0.1), (2, 10)], aT=0.5),
    mdrmap.Material(G=1, tau=1, temperature="35C", wlf=(8.86, 101.6, "25C")),
    mdrmap.Indenter(R=10),
    mdrmap.Indenter("cone", beta=10),
    mdrmap.Indenter("power", n=3, A=0.5),
    mdrmap.History([(1, 2), (0, 100), (1, 5)]),
    mdrmap.History("1:2,0:3"),
], ids=repr)
def test_the_repr_is_the_call_that_makes_it(obj):
    again = eval(repr(obj), {"mdrmap": mdrmap})
    assert again == obj and repr(again) == repr(obj)


def test_files(tmp_path):
    card = tmp_path / "rubber.inp"
    card.write_text("*MATERIAL, NAME=R\n*ELASTIC, MODULI=LONG TERM\n3.0, 0.5\n"
                    "*VISCOELASTIC, TIME=PRONY\n0.25, 0, 0.1\n0.25, 0, 10\n"
                    "*TRS, DEFINITION=WLF\n25, 8.86, 101.6\n")
    m = mdrmap.Material.from_file(card, temperature=35)
    assert repr(m) == f"mdrmap.Material.from_file({str(card)!r}, tau=0.0, temperature=35)"
    assert m.G == 1.0 and len(m.prony) == 2 and m.wlf == (8.86, 101.6, 25.0)
    a = mdrmap.simulate(material=m, R=10, d=0.1, v=1, v1=2, samples=5)
    b = mdrmap.simulate(material=card, tau=0, temperature=35, R=10, d=0.1, v=1, v1=2,
                        samples=5)
    same_run(a, b)
    spectrum = tmp_path / "spectrum.csv"
    spectrum.write_text("tau,E\n0.1,3\n10,6\n")
    p = mdrmap.Material.from_file(spectrum, G=1, nu=0.5)
    assert p.prony == [(1.0, 0.1), (2.0, 10.0)] and p.G == 1.0
    assert p == mdrmap.Material(G=1, prony=SPECTRUM)
    assert hash(p) == hash(mdrmap.Material(G=1, prony=SPECTRUM))  # equal: equal hashes
    assert mdrmap.Material(material=card, temperature=35) == m  # the keyword of simulate
    record = tmp_path / "record.csv"
    record.write_text("t,v\n10,1\n11,1\n12,0.5\n14,0.5\n15,0\n17,0\n")
    h = mdrmap.History.from_record(record)
    assert h.segments == [(1.0, 2.0), (0.5, 3.0), (0.0, 2.0)] and h.v == 1.0 and h.rows == 6
    assert repr(h) == f"mdrmap.History.from_record({str(record)!r})"
    same_run(mdrmap.simulate(history=h, R=10, d=0.1, tau=1),
             mdrmap.simulate(history_file=record, R=10, d=0.1, tau=1))


@pytest.mark.parametrize("make, keyword, said", [
    (lambda: mdrmap.Material(G=-1, tau=1), "G", "must be a finite number > 0, got -1"),
    (lambda: mdrmap.Material(G=1), "tau", "is required"),
    (lambda: mdrmap.Material(prony=[(1, 1)]), "G", "must be given with a spectrum"),
    (lambda: mdrmap.Material(G=1, prony=[(0, 1)]), "prony", "term 1 '0:1': G1 must be"),
    (lambda: mdrmap.Material(G=1, tau=1, temperature=20), "temperature", "needs --wlf"),
    (lambda: mdrmap.Material(G=1, tau=1, temperature=190, wlf=(8.86, 101.6, 298)),
     "temperature", "must be > TREF - C2"),
    # a bare temperature whose pair reads as the other scale (issue 33)
    (lambda: mdrmap.Material(G=1, tau=1, temperature=308.15, wlf=(8.86, 101.6, "25C")),
     "temperature", "give T its unit (308.15K or 308.15C)"),
    (lambda: mdrmap.Material(G=1, tau=1, aT=0), "aT", "must be a finite number > 0"),
    (lambda: mdrmap.Material(G=np.bool_(True), tau=1), "G", "must be a number, got True"),
    (lambda: mdrmap.Material.from_file("/no/such/file.inp"), "material", "/no/such/file.inp"),
    (lambda: mdrmap.Material(G=1, tau=1, nu=0.3), "nu", "applies to a spectrum file's"),
    (lambda: mdrmap.Indenter("cone"), "beta", "is required"),
    (lambda: mdrmap.Indenter("cone", beta=90), "beta", "must be a finite number > 0 and < 90"),
    (lambda: mdrmap.Indenter(R=10, beta=3), "beta", "applies to --profile cone only"),
    (lambda: mdrmap.Indenter("ellipsoid", R=1), "profile", "ellipsoid"),
    (lambda: mdrmap.Indenter(R=b"10"), "R", "must be a number, got bytes"),
    (lambda: mdrmap.Indenter("power", n=0.5, A=1), "n", "must be a finite number >= 1"),
    (lambda: mdrmap.History([(1, -2)]), "history", "segment 1 '1:-2': T must be"),
    (lambda: mdrmap.History([]), "history", "got none"),
    (lambda: mdrmap.History(), "history", "is required"),
    (lambda: mdrmap.History([(1, 2, 3)]), "history", "segment 1 must be a pair"),
    (lambda: mdrmap.simulate(material=mdrmap.Material(G=2, tau=1), G=1, R=10, d=0.1, v=1,
                             v1=2), "G", "is given twice"),
    (lambda: mdrmap.simulate(material=mdrmap.Indenter(R=10), tau=1, d=0.1, v=1, v1=2),
     "material", "must be a mdrmap.Material"),
    (lambda: mdrmap.simulate(indenter="cone", tau=1, d=0.1, v=1, v1=2), "indenter",
     "must be a mdrmap.Indenter"),
    (lambda: mdrmap.stationary(history=mdrmap.History([(1, 2)]), R=10, tau=1, d=0.1, v=1),
     "history", "not taken here"),
])
def test_bad_parts_are_refused_when_made_naming_the_keyword(make, keyword, said, capfd):
    with pytest.raises(mdrmap.InvalidInput) as e:
        make()
    assert e.value.keyword == keyword and said in e.value.message, str(e.value)
    assert capfd.readouterr() == ("", "")


def test_a_part_refuses_as_the_whole_call_does(exe):
    """The message of a part made alone is the command line's."""
    from conftest import run_cli

    with pytest.raises(mdrmap.InvalidInput) as e:
        mdrmap.Material(G=1, tau=1, temperature=20, wlf=(0, 51.6, 0))
    code, out, err = run_cli(exe, ["--d", "0.1", "--R", "10", "--tau", "1", "--v", "1", "--v1",
                                   "2", "--T", "20", "--wlf", "0:51.6:0"])
    assert code == 2 and err == f"mdrmap simulate: error: --wlf: {e.value.message}\n"


def test_a_fifo_is_refused_at_once(tmp_path):
    """A part's file is read without waiting on a FIFO (and without the GIL):
    refused naming the keyword. In a child process, so that a wait fails the
    test instead of hanging it."""
    import os
    import subprocess
    import sys

    fifo = tmp_path / "part.fifo"
    os.mkfifo(fifo)
    code = ("import sys, mdrmap\n"
            "for make in (mdrmap.Material.from_file, mdrmap.History.from_record):\n"
            "    try:\n"
            "        make(sys.argv[1])\n"
            "    except mdrmap.InvalidInput as e:\n"
            "        print(e.keyword, 'must be a regular file' in e.message)\n")
    try:
        p = subprocess.run([sys.executable, "-c", code, str(fifo)], capture_output=True,
                           text=True, timeout=60)
    except subprocess.TimeoutExpired:
        pytest.fail("a part made from a FIFO did not return within 60 s")
    assert p.stdout == "material True\nhistory_file True\n", (p.stdout, p.stderr)
