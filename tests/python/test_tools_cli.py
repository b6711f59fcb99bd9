"""The tools as `python -m mdrmap TOOL` (src/python/mdrmap/tools): --help
lists every tool and each tool's --help works; bad input is one line and exit
code 2; plot_run draws a run from mdrmap.simulate's arguments and from the
CSV the program wrote, the same numbers either way; Result.to_dataframe and
to_xarray hold the arrays of the result."""
import os
import subprocess
import sys

import numpy as np
import pytest

import mdrmap
from mdrmap.tools import TOOLS

CASE = dict(F0=0.0533, R=100, tau=1, v=1, history=[(1, 5), (0, 10), (2, 20)], samples=21)


def python_m(*args, cwd=None):
    p = subprocess.run([sys.executable, "-m", "mdrmap", *args], capture_output=True, text=True,
                       timeout=300, cwd=cwd)
    return p.returncode, p.stdout, p.stderr


def test_help_lists_every_tool_module():
    code, out, err = python_m("--help")
    assert code == 0 and err == ""
    listed = [ln.split()[0] for ln in out.splitlines() if ln.startswith("  ")]
    here = os.path.dirname(mdrmap.tools.__file__)
    modules = sorted(f[:-3] for f in os.listdir(here)
                     if f.endswith(".py") and not f.startswith("_"))
    assert sorted(listed) == modules == sorted(TOOLS)


@pytest.mark.parametrize("name", sorted(TOOLS))
def test_each_tool_has_help(name):
    pytest.importorskip("matplotlib")
    if name == "mapxr":
        pytest.importorskip("xarray")
    code, out, err = python_m(name, "--help")
    assert code == 0, err
    assert out.startswith(f"usage: python -m mdrmap {name} ")
    assert "Traceback" not in err
    # the hyphenated spelling names the same tool
    assert python_m(name.replace("_", "-"), "--help")[1] == out


@pytest.mark.parametrize("args,expected", [
    ((), "give a tool"),
    (("simulate", "--d", "1"), "no tool 'simulate'"),
    (("_maplib",), "no tool '_maplib'"),
    (("plot_run",), "give either mdrmap.simulate's KEY=VALUE arguments or --csv"),
    (("plot_run", "F0=1", "R=100", "tau=1"), "mdrmap.simulate: v: is required"),
    (("plot_run", "speed=3"), "not a keyword of mdrmap.simulate"),
    (("plot_run", "v"), "not a KEY=VALUE argument"),
    (("plot_run", "--csv", "absent.csv"), "no such file: absent.csv"),
    (("steps", "--F0", "1", "--prony", "1:x"), "--prony: not a number"),
    (("map_summary", "absent.h5"), "absent.h5"),
])
def test_bad_input_is_one_line_and_exit_2(args, expected, tmp_path):
    code, out, err = python_m(*args, cwd=tmp_path)
    assert code == 2, (out, err)
    assert err.count("\n") == 1 and expected in err, err
    assert not list(tmp_path.glob("*.png"))


def keywords(case):
    out = []
    for k, v in case.items():
        if k == "history":
            v = ",".join(f"{w}:{T}" for w, T in v)
        out.append(f"{k}={v}")
    return out


def printed_events(out):
    """The event rows plot_run prints, as lists of numbers."""
    lines = out.splitlines()
    k = next(i for i, ln in enumerate(lines) if ln.split()[:2] == ["k", "t"])
    return [[float(x) for x in ln.split()] for ln in lines[k + 1:] if ln[:1] == " "]


def test_plot_run_from_keywords_and_from_the_programs_csv(exe, tmp_path):
    pytest.importorskip("matplotlib")
    r = mdrmap.simulate(**CASE)
    code, out, err = python_m("plot_run", *keywords(CASE), "--x", "slip", "-o", "a.png",
                              cwd=tmp_path)
    assert code == 0, err
    assert (tmp_path / "a.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert f"{r.t.size} samples, {len(r.events)} events" in out
    mine = printed_events(out)
    assert len(mine) == len(r.events) == 3
    for row, e in zip(mine, r.events):
        assert row[0] == e["k"] and row[1] == pytest.approx(e["t"], rel=1e-4, abs=1e-12)
        assert row[5] == pytest.approx(e["mu_after"], rel=1e-4)
    csv = tmp_path / "run.csv"
    args = [exe, "simulate", "--F0", "0.0533", "--R", "100", "--tau", "1", "--v", "1",
            "--history", "1:5,0:10,2:20", "--samples", "21", "--output", str(csv)]
    subprocess.run(args, check=True, timeout=300)
    code, out2, err = python_m("plot_run", "--csv", "run.csv", "--scaled", "-o", "b.png",
                               cwd=tmp_path)
    assert code == 0, err
    np.testing.assert_array_equal(np.array(printed_events(out2)), np.array(mine))  # (nan = nan)
    assert (tmp_path / "b.png").stat().st_size > 10000


def test_plot_run_slip_is_the_integral_of_the_velocity():
    from mdrmap.tools import _runs, plot_run
    r = mdrmap.simulate(**CASE)
    run = _runs.from_result(r, "x")
    slip = plot_run.slip_of(run, np)
    # the trapezoid integral of the piecewise-constant velocity over the samples
    w = np.array([w for w, _ in r.case["history"]])[r.segment]
    dt = np.diff(r.t)
    steps = np.where(dt > 0, w[1:] * dt, 0.0)
    assert slip[0] == 0
    assert np.allclose(slip, np.concatenate([[0.0], np.cumsum(steps)]), rtol=1e-12, atol=1e-12)
    assert slip[-1] == pytest.approx(1 * 5 + 0 * 10 + 2 * 20)


@pytest.mark.parametrize("load", [True, False])
def test_to_dataframe_holds_the_arrays(load):
    pandas = pytest.importorskip("pandas")
    case = dict(CASE) if load else dict(d=0.01, R=100, tau=1, v=1, v1=3, samples=11)
    r = mdrmap.simulate(**case)
    df = r.to_dataframe()
    assert isinstance(df, pandas.DataFrame)
    want = ["t", "segment", "FN", "Fx", "mu", "a2"] + (["d", "a1"] if load else [])
    assert list(df.columns) == want == r.columns
    for name in want:
        assert np.array_equal(df[name].to_numpy(), getattr(r, name))
    assert df.attrs["pre"] == r.pre and df.attrs["scales"] == r.scales
    assert len(df.attrs["events"]) == len(r.events)
    df.attrs["pre"]["mu"] = -1.0  # a copy: the result keeps its own
    assert r.pre["mu"] != -1.0


def test_to_xarray_holds_the_arrays():
    pytest.importorskip("xarray")
    r = mdrmap.simulate(**CASE)
    ds = r.to_xarray()
    assert dict(ds.sizes) == {"sample": r.t.size}
    assert np.array_equal(ds["t"].values, r.t) and np.array_equal(ds["mu"].values, r.mu)
    assert np.array_equal(ds["d"].values, r.d) and ds.attrs["case"]["F0"] == 0.0533


def test_to_dataframe_without_pandas_is_one_clear_error(monkeypatch):
    r = mdrmap.simulate(**CASE)
    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas raises ImportError
    with pytest.raises(ImportError) as e:
        r.to_dataframe()
    text = str(e.value)
    assert "\n" not in text and "needs pandas" in text and "to_xarray()" in text


def test_plot_run_reads_a_cone_csv_of_the_program(exe, tmp_path):
    """A `# case` line with a word (profile=cone) is read, not refused."""
    pytest.importorskip("matplotlib")
    csv = tmp_path / "cone.csv"
    subprocess.run([exe, "simulate", "--profile", "cone", "--beta", "10", "--d", "0.1", "--tau",
                    "1", "--v", "1", "--v1", "10", "--samples", "11", "--output", str(csv)],
                   check=True, timeout=300)
    code, out, err = python_m("plot_run", "--csv", "cone.csv", "--x", "slip", "-o", "c.png",
                              cwd=tmp_path)
    assert code == 0, err
    r = mdrmap.simulate(profile="cone", beta=10, d=0.1, tau=1, v=1, v1=10, samples=11)
    assert f"mu before t = 0: {r.pre['mu']:.6g}" in out


def test_a_missing_module_is_one_line(tmp_path):
    """A tool whose plotting library this Python lacks says so in one line
    (exit 2), not with a traceback: a matplotlib that cannot be imported."""
    fake = tmp_path / "fake" / "matplotlib"
    fake.mkdir(parents=True)
    (fake / "__init__.py").write_text(
        "raise ModuleNotFoundError(\"No module named 'matplotlib'\", name='matplotlib')\n")
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(tmp_path / "fake"), os.environ.get("PYTHONPATH", "")]))
    p = subprocess.run([sys.executable, "-m", "mdrmap", "plot_run", *keywords(CASE), "-o",
                        "x.png"], capture_output=True, text=True, timeout=300, env=env,
                       cwd=tmp_path)
    assert p.returncode == 2, p.stderr
    assert p.stderr.count("\n") == 1 and "needs the Python module matplotlib" in p.stderr
    assert not (tmp_path / "x.png").exists()
