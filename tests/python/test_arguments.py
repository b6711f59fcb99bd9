"""The keywords as a Python user gives them: stationary over a list of
velocities (the CLI's --v-list), wlf as a tuple (as prony takes pairs),
temperature= (T= its old spelling), and help() listing every keyword of the
parameter table and of the command line."""
import os
import re
import subprocess

import numpy as np
import pytest

import mdrmap
from mdrmap import _core

CASE = dict(d=0.1, R=10, tau=1, G=1, prony=[(1.0, 0.1), (2.0, 10.0)])
SPECTRUM = dict(CASE, v=1, v1=2)


def test_stationary_over_a_list_is_the_cli_v_list(exe):
    vs = [0.01, 0.3, 1.0, 7.0]
    out = mdrmap.stationary(**CASE, v=vs)
    p = subprocess.run([exe, "stationary", "--d", "0.1", "--R", "10", "--tau", "1",
                        "--G", "1", "--prony", "1:0.1,2:10", "--v-list", "0.01,0.3,1,7"],
                       capture_output=True, text=True, timeout=60, check=True)
    rows = [line.split(",") for line in p.stdout.splitlines() if not line.startswith("#")]
    header, rows = rows[0], rows[1:]
    assert {"v", "FN", "Fx", "mu", "a2"} <= set(header) and set(out) <= set(header)
    for j, name in enumerate(header):
        if name not in out:  # (d and a1 at fixed depth: the module leaves them out)
            continue
        assert np.array_equal(out[name], [float(r[j]) for r in rows]), name
    for k, v in enumerate(vs):  # each state as one velocity gives it
        one = mdrmap.stationary(**CASE, v=v)
        assert all(one[name] == out[name][k] for name in one)
    assert np.array_equal(mdrmap.stationary(**CASE, v=np.array(vs))["mu"], out["mu"])


def test_a_bad_velocity_of_the_list_names_v():
    with pytest.raises(mdrmap.InvalidInput, match=r"^v: item 2 must be a velocity") as e:
        mdrmap.stationary(**CASE, v=[1, -1])
    assert e.value.option == "v-list" and e.value.keyword == "v"


def test_wlf_as_a_tuple_is_its_text():
    a = mdrmap.simulate(**SPECTRUM, temperature=310, wlf=(8.86, 101.6, 298))
    b = mdrmap.simulate(**SPECTRUM, temperature=310, wlf="8.86:101.6:298")
    assert np.array_equal(a.mu, b.mu) and a.case["aT"] == b.case["aT"] < 1
    with pytest.raises(mdrmap.InvalidInput, match=r"^wlf: must be the three WLF constants"):
        mdrmap.simulate(**SPECTRUM, temperature=310, wlf=(8.86, 101.6))


def test_temperature_is_the_keyword_and_T_its_old_spelling():
    a = mdrmap.simulate(**SPECTRUM, temperature=310, wlf=(8.86, 101.6, 298))
    b = mdrmap.simulate(**SPECTRUM, T=310, wlf=(8.86, 101.6, 298))
    assert np.array_equal(a.mu, b.mu)
    s = mdrmap.stationary(**CASE, v=1, temperature=310, wlf=(8.86, 101.6, 298))
    assert s == mdrmap.stationary(**CASE, v=1, T=310, wlf=(8.86, 101.6, 298))
    with pytest.raises(mdrmap.InvalidInput, match=r"^temperature: must be > TREF - C2") as e:
        mdrmap.simulate(**SPECTRUM, temperature=190, wlf=(8.86, 101.6, 298))
    assert e.value.option == "T" and e.value.keyword == "temperature"
    with pytest.raises(mdrmap.InvalidInput, match="may be given only once"):
        mdrmap.simulate(**SPECTRUM, temperature=310, T=310, wlf=(8.86, 101.6, 298))


def documented(doc):
    """The keywords of a generated docstring's list, and their texts."""
    lines = doc.split("Keyword arguments")[1].splitlines()[1:]
    out = {}
    for line in lines:
        if line.startswith("    ") and not line.startswith("     "):
            kw, _, text = line.strip().partition(" ")
            out[kw] = text
    return out


def test_help_documents_every_parameter():
    table = {p["name"].replace("-", "_") for p in _core.parameter_table()}
    options = {o.replace("-", "_") for o in _core.option_names()} - {"T"} | {"temperature"}
    sim = documented(mdrmap.simulate.__doc__)
    assert table <= set(sim) and options <= set(sim) and "progress" in sim
    assert not any("(undocumented)" in t for t in sim.values())
    st = documented(mdrmap.stationary.__doc__)
    assert {"v", "d", "F0", "R", "tau", "G", "aT", "beta", "n", "A", "profile", "prony",
            "prony_file", "temperature", "wlf", "progress"} <= set(st)
    assert "(undocumented)" not in mdrmap.stationary.__doc__
    doc = " ".join(mdrmap.simulate.__doc__.split())
    for p in _core.parameter_table():  # the table's own words, --OPTION as its keyword
        assert python_words(" ".join(p["meaning"].split()[:4])) in doc


def python_words(text):
    """The CLI's words with keywords for its options: --prony-file as prony_file."""
    def keyword(m):
        return "temperature" if m.group(1) == "T" else m.group(1).replace("-", "_")
    return re.sub(r"--([A-Za-z][A-Za-z0-9-]*)", keyword, text)


def test_option_texts_come_from_the_command_line_help():
    """One text an option (issue 34): the keywords outside the table are
    documented in the words of the CLI's help (_core.option_help), their
    default included; only the value's Python form is written in Python."""
    help_ = _core.option_help()
    assert {"prony", "history", "rtol", "solver", "spacing", "wlf", "T"} <= set(help_)
    doc = " ".join(mdrmap.simulate.__doc__.split())
    cli = subprocess.run([os.environ["MDRMAP_EXE"], "simulate", "--help-all"], check=True,
                         capture_output=True, text=True).stdout
    cli = " ".join(cli.split())
    for name, h in help_.items():
        words = " ".join(h["text"].split()[:6])
        assert words in cli, name  # the CLI's help says it ...
        assert " ".join(python_words(h["text"]).split()[:6]) in doc, name  # ... and Python
        if h["default"] is not None:
            assert "Default: " + h["default"] in cli, name
    assert '[(G1, tau1), (G2, tau2), ...] (or "G1:TAU1,G2:TAU2,..."): the Maxwell' in doc
    assert "with prony: no parallel dashpot" in doc and "--" not in doc


def test_prony_file_columns_by_name(tmp_path):
    """Issue 33: E with nu, or g normalised by '# G0 = ...' (then G = G0 (1 - sum g))."""
    young = tmp_path / "E.csv"
    young.write_text("tau,E\n0.1,3\n10,6\n")
    norm = tmp_path / "g.csv"
    norm.write_text("# G0 = 4\ng,tau\n0.25,0.1\n0.5,10\n")
    kw = dict(d=0.1, R=10, tau=0, v=1)
    a = mdrmap.stationary(**kw, G=1, prony_file=young)
    b = mdrmap.stationary(**kw, prony_file=norm)
    c = mdrmap.stationary(**kw, G=1, prony=[(1.0, 0.1), (2.0, 10.0)])
    assert a == c and b == c
    with pytest.raises(mdrmap.InvalidInput) as e:
        mdrmap.stationary(**kw, G=1, prony_file=young, nu=0.7)
    assert e.value.option == "nu"


def test_temperatures_have_units():
    """Issue 33: temperature= and wlf's TREF take C or K; a mix is converted;
    a shift beyond 12 decades is refused unless allow_large_shift=True."""
    kw = dict(d=0.1, R=10, tau=1, v=1)
    a = mdrmap.stationary(**kw, temperature=35, wlf=(8.86, 101.6, 25))
    b = mdrmap.stationary(**kw, temperature="35C", wlf=(8.86, 101.6, "298.15K"))
    c = mdrmap.stationary(**kw, temperature="308.15K", wlf="8.86:101.6:25C")
    assert a["mu"] == pytest.approx(b["mu"], rel=1e-12) and b["mu"] == pytest.approx(c["mu"], rel=1e-12)
    with pytest.raises(mdrmap.InvalidInput) as e:
        mdrmap.stationary(**kw, temperature="25C", wlf=(17.44, 51.6, "-100C"))
    assert e.value.keyword == "temperature" and "12 decades" in e.value.message
    mdrmap.stationary(**kw, temperature="25C", wlf=(17.44, 51.6, "-100C"), allow_large_shift=True)
    # a bare number whose pair reads as the other scale: 308.15 against 25C
    # (35C read as 308.15C, log10 aT = -6.5, within the 12 decades) is refused
    with pytest.raises(mdrmap.InvalidInput, match=r"give T its unit \(308.15K or 308.15C\)") as e:
        mdrmap.stationary(**kw, temperature=308.15, wlf=(8.86, 101.6, "25C"))
    assert e.value.keyword == "temperature" and "\n" not in e.value.message
    assert mdrmap.stationary(**kw, temperature="308.15K", wlf=(8.86, 101.6, "25C")) == c


def test_material_card_is_the_spectrum(tmp_path):
    """Issue 33: an Abaqus card (instantaneous E, g_i normalised by G0) is its spectrum."""
    card = tmp_path / "rubber.inp"
    card.write_text("*MATERIAL, NAME=R\n*ELASTIC, MODULI=INSTANTANEOUS\n12., 0.5\n"
                    "*VISCOELASTIC, TIME=PRONY\n0.25, 0., 0.1\n0.5, 0., 10.\n")
    kw = dict(d=0.1, R=10, tau=0, v=1)
    a = mdrmap.stationary(**kw, material=card)
    b = mdrmap.stationary(**kw, G=1, prony=[(1.0, 0.1), (2.0, 10.0)])
    assert a == b
    with pytest.raises(mdrmap.InvalidInput) as e:
        mdrmap.stationary(**kw, material=card, G=1)
    assert e.value.option == "G"
