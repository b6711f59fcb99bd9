"""Every bad-input row of the CLI's tests (tests/test_cli.cpp: SimulateBad*)
raises mdrmap.InvalidInput (a ValueError) naming the same option, with the
CLI's message, and prints nothing. The rows are copied here; the test checks
that the copy lists every row of test_cli.cpp."""
import os
import re

import pytest

import mdrmap
from conftest import run_cli

DROP = None  # the row removes the option
BASE = {"d": "0.1", "R": "10", "tau": "1", "G": "1", "v": "2", "v1": "0.5"}
CLI_PREFIX = "mdrmap simulate: error: "

# (label, {option: text or DROP}, extra CLI tokens, option named)
ROWS = [
    ("d = 0", {"d": "0"}, [], "d"),
    ("d < 0", {"d": "-1"}, [], "d"),
    ("R = 0", {"R": "0"}, [], "R"),
    ("R < 0", {"R": "-10"}, [], "R"),
    ("G = 0", {"G": "0"}, [], "G"),
    ("G < 0", {"G": "-1"}, [], "G"),
    ("v = 0", {"v": "0"}, [], "v"),
    ("v < 0", {"v": "-2"}, [], "v"),
    ("tau < 0", {"tau": "-1"}, [], "tau"),
    ("v1 < 0", {"v1": "-0.5"}, [], "v1"),
    ("d = nan", {"d": "nan"}, [], "d"),
    ("tau = nan", {"tau": "NaN"}, [], "tau"),
    ("R = inf", {"R": "inf"}, [], "R"),
    ("v1 = inf", {"v1": "infinity"}, [], "v1"),
    ("v = -inf", {"v": "-inf"}, [], "v"),
    ("d = 1e999 (overflow)", {"d": "1e999"}, [], "d"),
    ("d not a number", {"d": "abc"}, [], "d"),
    ("d trailing junk", {"d": "0.1mm"}, [], "d"),
    ("d empty", {"d": ""}, [], "d"),
    ("samples = 1", {"samples": "1"}, [], "samples"),
    ("samples = 0", {"samples": "0"}, [], "samples"),
    ("samples = -3", {"samples": "-3"}, [], "samples"),
    ("samples = 2.5", {"samples": "2.5"}, [], "samples"),
    ("samples = 1e99", {"samples": "1e99"}, [], "samples"),
    ("samples = abc", {"samples": "abc"}, [], "samples"),
    ("samples too many", {"samples": "100000001"}, [], "samples"),
    ("samples beyond long", {"samples": "99999999999999999999999"}, [], "samples"),
    ("t-end = 0", {"t-end": "0"}, [], "t-end"),
    ("t-end < 0", {"t-end": "-1"}, [], "t-end"),
    ("t-end = nan", {"t-end": "nan"}, [], "t-end"),
    ("rtol = 0", {"rtol": "0"}, [], "rtol"),
    ("rtol = 0.2", {"rtol": "0.2"}, [], "rtol"),
    ("rtol < 0", {"rtol": "-1"}, [], "rtol"),
    ("rtol = nan", {"rtol": "nan"}, [], "rtol"),
    ("unknown solver", {"solver": "fast"}, [], "solver"),
    ("unknown option", {}, ["--speed", "3"], "speed"),
    ("wrong case option", {}, ["--g", "3"], "g"),
    ("F0 = 0", {"d": DROP, "F0": "0"}, [], "F0"),
    ("F0 < 0", {"d": DROP, "F0": "-1"}, [], "F0"),
    ("F0 = nan", {"d": DROP, "F0": "nan"}, [], "F0"),
    ("F0 = inf", {"d": DROP, "F0": "inf"}, [], "F0"),
    ("F0 not a number", {"d": DROP, "F0": "1N"}, [], "F0"),
    ("d = 0 beside F0", {"d": "0", "F0": "1"}, [], "d"),
    ("F0 = -1 beside d", {"F0": "-1"}, [], "F0"),
    ("F0 twice", {"d": DROP, "F0": "1"}, ["--F0", "2"], "F0"),
    # FN, the old spelling of F0: its errors name it as given
    ("FN = 0", {"d": DROP, "FN": "0"}, [], "FN"),
    ("FN not a number", {"d": DROP, "FN": "1N"}, [], "FN"),
    ("FN twice", {"d": DROP, "FN": "1"}, ["--FN", "2"], "FN"),
    ("fn (case)", {}, ["--fn", "1"], "fn"),
    ("missing --v1", {"v1": DROP}, [], "v1"),
    ("--d twice", {}, ["--d", "0.2"], "d"),
    ("--v1 and --history", {}, ["--history", "0.5:6"], "history"),
    ("--t-end with --history", {"v1": DROP}, ["--history", "0.5:6", "--t-end", "6"], "t-end"),
    ("--history twice", {"v1": DROP}, ["--history", "1:1", "--history", "2:2"], "history"),
    ("spacing unknown", {"spacing": "lin"}, [], "spacing"),
    ("log-decades without log spacing", {"log-decades": "3"}, [], "log-decades"),
    ("log-decades = 0", {"spacing": "log", "log-decades": "0"}, [], "log-decades"),
    ("log-decades > 300", {"spacing": "log", "log-decades": "301"}, [], "log-decades"),
    ("samples x segments too many", {"v1": DROP, "samples": "60000000"},
     ["--history", "1:1,2:2"], "samples"),
    ("--d without value", {"d": DROP}, ["--d"], "d"),
    ("contact radius below 1e-75", {"R": "1e-300"}, [], "d"),
    ("contact radius above 1e75", {"R": "1e300", "d": "1e10"}, [], "d"),
    ("w tau / a overflows by a segment's W", {"v1": DROP, "d": "1e-60", "R": "1e-60"},
     ["--history", "1e300:1"], "history"),
    ("w tau overflows by a segment's W", {"v1": DROP, "d": "1", "R": "1"},
     ["--history", "1e308:1"], "history"),
    ("slip W T overflows", {"v1": DROP}, ["--history", "1e300:1e300"], "history"),
    ("under load a segment's W shrinks the contact below 1e-75",
     {"v1": DROP, "d": DROP, "FN": "5.333333333333333", "R": "1"}, ["--history", "5e307:1"],
     "history"),
    # relaxation spectra and the temperature shift (issue 19); {dir} is a
    # directory holding PRONY_FILES
    # indenter profiles (issue 21)
    ("profile unknown", {"profile": "ellipsoid"}, [], "profile"),
    ("--beta with the parabola", {"beta": "10"}, [], "beta"),
    ("--n with the parabola", {"n": "2"}, [], "n"),
    ("--R with a cone", {"profile": "cone", "beta": "10"}, [], "R"),
    ("--A with a cone", {"profile": "cone", "beta": "10", "R": DROP, "A": "1"}, [], "A"),
    ("cone without --beta", {"profile": "cone", "R": DROP}, [], "beta"),
    ("beta = 0", {"profile": "cone", "R": DROP, "beta": "0"}, [], "beta"),
    ("beta = 90", {"profile": "cone", "R": DROP, "beta": "90"}, [], "beta"),
    ("beta < 0", {"profile": "cone", "R": DROP, "beta": "-10"}, [], "beta"),
    ("n < 1", {"profile": "power", "R": DROP, "n": "0.5", "A": "1"}, [], "n"),
    ("A = 0", {"profile": "power", "R": DROP, "n": "2", "A": "0"}, [], "A"),
    ("A < 0", {"profile": "power", "R": DROP, "n": "2", "A": "-1"}, [], "A"),
    ("power without --A", {"profile": "power", "R": DROP, "n": "2"}, [], "A"),
    ("--R with power", {"profile": "power", "n": "2", "A": "1"}, [], "R"),
    ("a cone on the continuum solver",
     {"profile": "cone", "R": DROP, "beta": "10", "solver": "exact"}, [], "profile"),
    ("the retired mdr solver", {"solver": "mdr"}, [], "solver"),
    ("an unknown solver", {"solver": "spectrum_baseline"}, [], "solver"),
    ("prony without --G", {"G": DROP, "prony": "1:1"}, [], "G"),
    ("prony-file without --G", {"G": DROP, "prony-file": "{dir}/good.csv"}, [], "G"),
    ("prony G = 0", {"prony": "0:1"}, [], "prony"),
    ("prony G < 0", {"prony": "1:1,-2:10"}, [], "prony"),
    ("prony tau = 0", {"prony": "1:0"}, [], "prony"),
    ("prony tau < 0", {"prony": "1:-1"}, [], "prony"),
    ("prony G = nan", {"prony": "nan:1"}, [], "prony"),
    ("prony tau = inf", {"prony": "1:inf"}, [], "prony"),
    ("prony tau overflows", {"prony": "1:1e999"}, [], "prony"),
    ("prony term without its time", {"prony": "5:"}, [], "prony"),
    ("prony term without its modulus", {"prony": ":2"}, [], "prony"),
    ("prony term without ':'", {"prony": "1:1,5"}, [], "prony"),
    ("prony term with two ':'", {"prony": "1:1:1"}, [], "prony"),
    ("prony empty term", {"prony": "1:1,,2:2"}, [], "prony"),
    ("prony empty", {"prony": ""}, [], "prony"),
    ("prony not a number", {"prony": "1:2s"}, [], "prony"),
    ("prony 33 terms", {"prony": ",".join(["1:2"] * 33)}, [], "prony"),
    ("prony and prony-file", {"prony": "1:1", "prony-file": "{dir}/bad_tau.csv"}, [],
     "prony-file"),
    ("prony-file missing", {"prony-file": "{dir}/no_such_dir/p.csv"}, [], "prony-file"),
    ("prony-file is a directory", {"prony-file": "{dir}"}, [], "prony-file"),
    ("prony-file without header", {"prony-file": "{dir}/no_header.csv"}, [], "prony-file"),
    ("prony-file without terms", {"prony-file": "{dir}/only_header.csv"}, [], "prony-file"),
    ("prony-file tau < 0", {"prony-file": "{dir}/bad_tau.csv"}, [], "prony-file"),
    ("prony-file half a term", {"prony-file": "{dir}/half_term.csv"}, [], "prony-file"),
    ("prony-file three values", {"prony-file": "{dir}/three_values.csv"}, [], "prony-file"),
    ("prony-file 33 terms", {"prony-file": "{dir}/too_many.csv"}, [], "prony-file"),
    ("aT = 0", {"aT": "0"}, [], "aT"),
    ("aT = inf", {"aT": "inf"}, [], "aT"),
    ("aT shifts a time beyond a double", {"aT": "1e300", "prony": "1:1e10"}, [], "aT"),
    ("aT shifts tau beyond a double", {"aT": "1e300", "tau": "1e10"}, [], "aT"),
    ("T without wlf", {"T": "20"}, [], "T"),
    ("wlf without T", {"wlf": "17.44:51.6:0"}, [], "wlf"),
    ("T with aT", {"T": "20", "wlf": "17.44:51.6:0", "aT": "2"}, [], "T"),
    ("T = TREF - C2", {"T": "-50", "wlf": "10:50:0"}, [], "T"),
    ("T below TREF - C2", {"T": "-60", "wlf": "17.44:51.6:0"}, [], "T"),
    ("T = nan", {"T": "nan", "wlf": "17.44:51.6:0"}, [], "T"),
    ("T shifts a time beyond a double", {"T": "-0.99", "wlf": "1:1:0", "prony": "1:1e250"}, [],
     "T"),
    ("T gives an aT beyond a double", {"T": "-49.99", "wlf": "17.44:50:0"}, [], "T"),
    ("wlf with two constants", {"T": "20", "wlf": "17.44:51.6"}, [], "wlf"),
    ("wlf C1 = 0", {"T": "20", "wlf": "0:51.6:0"}, [], "wlf"),
    ("wlf C2 < 0", {"T": "20", "wlf": "17.44:-51.6:0"}, [], "wlf"),
    ("wlf TREF not a number", {"T": "20", "wlf": "17.44:51.6:room"}, [], "wlf"),
    ("wlf TREF = inf", {"T": "20", "wlf": "17.44:51.6:inf"}, [], "wlf"),
    ("T in F", {"T": "20F", "wlf": "17.44:51.6:0"}, [], "T"),
    ("T below absolute zero", {"T": "-300C", "wlf": "17.44:51.6:0C"}, [], "T"),
    ("T below 0K", {"T": "-1K", "wlf": "17.44:51.6:0C"}, [], "T"),
    ("wlf TREF below 0K", {"T": "20C", "wlf": "17.44:51.6:-5K"}, [], "wlf"),
    ("T more than 12 decades from TREF", {"T": "25C", "wlf": "17.44:51.6:-100C"}, [], "T"),
    ("T 25 against TREF 298.15K", {"T": "25", "wlf": "8.86:101.6:298.15K"}, [], "T"),
    # a bare number whose pair reads as the other scale: a shift the 12 decades miss
    ("T 308.15 against TREF 25C", {"T": "308.15", "wlf": "8.86:101.6:25C"}, [], "T"),
    ("T 35C against TREF 298.15", {"T": "35C", "wlf": "8.86:101.6:298.15"}, [], "T"),
    ("T 308.15 against TREF 25, both bare", {"T": "308.15", "wlf": "8.86:101.6:25"}, [], "T"),
    ("allow-large-shift without T", {"aT": "2", "allow-large-shift": "true"}, [],
     "allow-large-shift"),
    ("allow-large-shift not a flag",
     {"T": "20", "wlf": "17.44:51.6:0", "allow-large-shift": "maybe"}, [], "allow-large-shift"),
    ("prony on the exact solver", {"prony": "1:1,2:10", "solver": "exact"}, [], "prony"),
    ("prony-file on the Kelvin solvers", {"prony-file": "{dir}/good.csv", "solver": "exact"}, [],
     "prony"),
]
# The spectrum files of the rows above, as test_cli.cpp writes them.
PRONY_FILES = {
    "no_header.csv": "1,2\n",
    "only_header.csv": "# spectrum\nG,tau\n\n",
    "bad_tau.csv": "G,tau\n1,2\n# comment\n3,-4\n",
    "half_term.csv": "G,tau\n1,\n",
    "three_values.csv": "G,tau\n1,2,3\n",
    "too_many.csv": "G,tau\n" + "1,2\n" * 33,
    "good.csv": "G,tau\n1,2\n3,40\n",
}
# Rows about --output: the module writes no file.
OUTPUT_ROWS = {"output into a missing directory", "output into a read-only directory",
               "output below a regular file", "output is a directory", "output empty"}
# Rows that give an option twice: a keyword argument cannot be repeated in a call
# (Python's own TypeError); the module's own check covers a keyword given in both
# spellings (t_end and t-end).
TWICE_ROWS = {"F0 twice", "FN twice", "--d twice", "--history twice"}
# Rows whose message is the module's own (keywords, not options): the option matches.
OWN_MESSAGE_ROWS = {"unknown option", "wrong case option", "fn (case)", "--d without value"}

HISTORY_ROWS = [
    ("empty history", ""), ("blank history", "  "), ("missing colon", "1:2,5"),
    ("extra colon", "1:2:3"), ("W not a number", "1:2,abc:1"), ("T not a number", "1:2x"),
    ("W empty", ":5"), ("T empty", "1:"), ("W < 0", "1:1,-1:2"), ("T = 0", "1:0"),
    ("T < 0", "1:-3"), ("W = nan", "nan:1"), ("T = inf", "1:inf"), ("W = -inf", "-inf:1"),
    ("T overflows", "1:1e999"), ("empty item", "1:2,,3:4"), ("leading comma", ",1:2"),
    ("trailing comma", "1:2,"), ("too many segments", ",".join(["1:1"] * 10001)),
    ("durations overflow", "1:1e308,1:1e308"),
]


def cli_rows(srcdir, test, pattern):
    """The labels of the rows of TEST(cli, <test>) in tests/test_cli.cpp."""
    with open(f"{srcdir}/tests/test_cli.cpp") as f:
        src = f.read()
    body = src[src.index(f"TEST(cli, {test})"):]
    body = body[:body.index("\nTEST(")]
    return re.findall(pattern, body)


def test_the_rows_are_the_cli_tests_rows(srcdir):
    # a row: {"label", {changes}, {extra}, "option"...}
    labels = cli_rows(srcdir, "SimulateBadInputsExit2WithOneLineNamingTheOption",
                      r'\{"([^"]+)",\s*\{')
    assert len(labels) >= 60
    assert sorted(labels) == sorted([r[0] for r in ROWS] + list(OUTPUT_ROWS))
    # a row: {"label", "history", {fragments}}
    labels = cli_rows(srcdir, "SimulateBadHistoryTokensExit2WithOneLineNamingHistory",
                      r'\{"([^"]+)",\s*(?:"[^"]*"|too_many),\s*\{')
    assert sorted(labels) == sorted(r[0] for r in HISTORY_ROWS)


def cli_and_keywords(row):
    """The CLI's arguments of a row, and the same as keyword arguments."""
    _, changes, extra, _ = row
    opts = dict(BASE)
    opts.update(changes)
    args, kw = [], {}
    for key, value in opts.items():
        if value is not DROP:
            args += ["--" + key, value]
            kw[key.replace("-", "_")] = value
    args += extra
    toks = list(extra)
    while toks:
        key = toks.pop(0)[2:]
        kw[key.replace("-", "_")] = toks.pop(0) if toks else None
    return args, kw


def cli_error(exe, args):
    code, out, err = run_cli(exe, args)
    assert code == 2 and out == "" and err.count("\n") == 1, err
    assert err.startswith(CLI_PREFIX)
    return err[len(CLI_PREFIX):].rstrip("\n")


def with_files(row, directory):
    """The row with {dir} replaced by a directory holding PRONY_FILES."""
    label, changes, extra, option = row
    if not any("{dir}" in str(v) for v in changes.values()):
        return row
    for name, text in PRONY_FILES.items():
        (directory / name).write_text(text)
    changes = {k: v.replace("{dir}", str(directory)) if isinstance(v, str) else v
               for k, v in changes.items()}
    return label, changes, extra, option


@pytest.mark.parametrize("row", [r for r in ROWS if r[0] not in TWICE_ROWS], ids=lambda r: r[0])
def test_bad_input_raises_invalid_input_naming_the_option(exe, row, capfd, tmp_path):
    args, kw = cli_and_keywords(with_files(row, tmp_path))
    with pytest.raises(mdrmap.InvalidInput) as e:
        mdrmap.simulate(**kw)
    assert isinstance(e.value, ValueError)
    assert e.value.option == row[3]
    assert e.value.keyword == row[3].replace("-", "_")
    line = cli_error(exe, args)
    assert line.startswith(f"--{row[3]}: ")
    if row[0] not in OWN_MESSAGE_ROWS:
        assert e.value.message == line[len(f"--{row[3]}: "):]
        assert str(e.value) == f"{e.value.keyword}: {e.value.message}"
    assert capfd.readouterr() == ("", "")


@pytest.mark.parametrize("row", [r for r in ROWS if r[0] in TWICE_ROWS], ids=lambda r: r[0])
def test_an_option_twice_is_refused(row):
    _, kw = cli_and_keywords(row)
    key = row[3].replace("-", "_")
    assert key in kw
    with pytest.raises(TypeError, match="multiple values"):
        mdrmap.simulate(**kw, **{key: "1"})  # Python's own refusal
    # both spellings of one option: the module's refusal
    with pytest.raises(mdrmap.InvalidInput) as e:
        mdrmap.simulate(**dict(BASE, spacing="log", log_decades="3", **{"log-decades": "3"}))
    assert e.value.option == "log-decades" and "only once" in e.value.message


@pytest.mark.parametrize("row", HISTORY_ROWS, ids=lambda r: r[0])
def test_bad_history_tokens_raise_naming_history(exe, row):
    kw = {k: v for k, v in BASE.items() if k != "v1"}
    with pytest.raises(mdrmap.InvalidInput) as e:
        mdrmap.simulate(**kw, history=row[1])
    assert e.value.option == "history"
    args = [x for k, v in kw.items() for x in ("--" + k, v)] + ["--history", row[1]]
    assert cli_error(exe, args) == "--history: " + e.value.message


def test_numbers_are_refused_as_their_texts():
    base = dict(d=0.1, R=10, tau=1, v=2, v1=0.5)
    cases = [({"d": 0}, "d", "must be a finite number > 0, got 0"),
             ({"d": -1.0}, "d", "got -1"),
             ({"tau": float("nan")}, "tau", "got nan"),
             ({"samples": 2.5}, "samples", "got 2.5"),
             ({"samples": 1}, "samples", "got 1"),
             ({"v1": float("inf")}, "v1", "got inf"),
             ({"d": True}, "d", "must be a number, got True"),
             ({"d": [1, 2]}, "d", "must be a number"),
             ({"d": None}, "d", "needs a value"),
             ({"F0": 1}, "", "give exactly one of --d D or --F0 F0"),
             ({"FN": 1}, "", "give exactly one of --d D or --F0 F0"),
             ({"v1": None, "history": [(1, 2, 3)]}, "history", "segment 1 must be a pair"),
             ({"v1": None, "history": 5}, "history", "must be a list of segments"),
             ({"v1": None, "history": []}, "history", "segments (W, T), its velocity W then its duration T; got none"),
             ({"v1": None, "history": [(1, -2)]}, "history", "segment 1 '1:-2': T must be")]
    for change, option, said in cases:
        kw = {k: v for k, v in dict(base, **change).items() if not (k == "v1" and v is None
                                                                     and "history" in change)}
        with pytest.raises(mdrmap.InvalidInput) as e:
            mdrmap.simulate(**kw)
        assert e.value.option == option, change
        assert said in e.value.message, (change, e.value.message)


def test_booleans_bytes_and_paths_are_not_numbers(tmp_path):
    """Issue 32: numpy's bool_, bytes and a pathlib.Path passed as numbers
    (float() takes all three) are refused naming the argument; a spectrum
    file is taken as a pathlib.Path."""
    import pathlib

    import numpy as np

    base = dict(d=0.1, R=10, tau=1, v=2, v1=0.5)
    cases = [({"d": np.bool_(True)}, "d", "must be a number, got True"),
             ({"tau": np.bool_(False)}, "tau", "must be a number, got False"),
             ({"d": b"0.1"}, "d", "must be a number, got bytes b'0.1'"),
             ({"v": bytearray(b"2")}, "v", "must be a number, got bytearray"),
             ({"R": pathlib.Path("10")}, "R", "must be a number, got a path '10'"),
             ({"samples": np.bool_(True)}, "samples", "got True")]
    for change, option, said in cases:
        with pytest.raises(mdrmap.InvalidInput) as e:
            mdrmap.simulate(**dict(base, **change))
        assert e.value.option == option, change
        assert said in e.value.message, (change, e.value.message)
    spectrum = tmp_path / "spectrum.csv"
    spectrum.write_text("G,tau\n1,0.5\n")
    kw = dict(d=0.1, R=10, tau=0, G=1, v=1)
    assert mdrmap.stationary(**kw, prony_file=spectrum) == \
        mdrmap.stationary(**kw, prony_file=str(spectrum))


def test_a_solver_refusing_the_loading_is_bad_input(exe):
    kw = dict(F0="0.1", R="10", tau="1", v="1", v1="2", solver="exact")
    with pytest.raises(mdrmap.InvalidInput) as e:  # refused by the solver, the GIL released
        mdrmap.simulate(**kw)
    assert e.value.option == "solver"
    args = [x for k, v in kw.items() for x in ("--" + k, v)]
    assert cli_error(exe, args) == "--solver: " + e.value.message


def test_a_case_past_its_budget_is_a_runtime_error():
    with pytest.raises(RuntimeError, match="rtol"):
        mdrmap.simulate(d=1e-3, R=1, tau=1, v=1, history="0.1:0.1,0:0.1,1:0.1", samples=5,
                        solver="row", rtol=1e-15)


def test_a_spectrum_file_that_is_a_fifo_is_refused_at_once(tmp_path):
    """Issue 32: prony_file on a FIFO without a writer waited for ever (and
    held the GIL, freezing every thread); now refused naming the option. In a
    child process, so that the old behaviour fails the test instead of
    hanging it."""
    import subprocess
    import sys

    fifo = tmp_path / "spectrum.fifo"
    os.mkfifo(fifo)
    code = ("import sys, mdrmap\n"
            "try:\n"
            "    mdrmap.stationary(d=0.1, R=10, tau=0, v=1, prony_file=sys.argv[1])\n"
            "except mdrmap.InvalidInput as e:\n"
            "    print(e.option, e.message)\n")
    try:
        p = subprocess.run([sys.executable, "-c", code, str(fifo)], capture_output=True,
                           text=True, timeout=60)
    except subprocess.TimeoutExpired:
        pytest.fail("mdrmap.stationary(prony_file=FIFO) did not return within 60 s")
    assert p.stdout == f"prony-file must be a regular file, got '{fifo}' (a FIFO)\n", \
        (p.stdout, p.stderr)
