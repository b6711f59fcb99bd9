"""The prescribed normal load is F0, the measured normal force FN (issue 22):
FN, the load's old name, is still taken as F0 wherever a case parameter is
spelled (keywords, options, config keys, case-list columns), both at once are
refused, the outputs name the load F0 (/cases/F0, /grid/F0, `# case F0=`),
and maps and CSVs written before the rename are read (and resumed) with the
load as F0."""
import os
import subprocess

import numpy as np
import pytest

import mdrmap

H5PY = pytest.importorskip("h5py")

LOAD = dict(R=10, tau=1, v=1, history=[(0.1, 5), (1, 5)], samples=7)
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def test_simulate_takes_fn_as_f0():
    a = mdrmap.simulate(F0=0.1, **LOAD)
    b = mdrmap.simulate(FN=0.1, **LOAD)
    assert a.load and b.load
    for name in ("t", "segment", "FN", "Fx", "mu", "a2", "d", "a1"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name
    assert str(a.events) == str(b.events)  # (nan != nan)
    assert a.pre == b.pre and a.case == b.case
    assert a.case["F0"] == 0.1 and "FN" not in a.case
    # FN of the result is the measured force, which load control holds at F0
    assert a.pre["FN"] == pytest.approx(0.1, rel=1e-12)
    stationary = dict(R=10, tau=1, v=1)
    assert mdrmap.stationary(F0=0.1, **stationary) == mdrmap.stationary(FN=0.1, **stationary)


def test_both_spellings_are_refused():
    for call in (mdrmap.simulate, mdrmap.stationary):
        kw = dict(LOAD) if call is mdrmap.simulate else dict(R=10, tau=1, v=1)
        with pytest.raises(mdrmap.InvalidInput) as e:
            call(F0=0.1, FN=0.1, **kw)
        assert e.value.option == ""
        assert e.value.message == ("--F0 and --FN are the same parameter (FN is the old "
                                   "spelling of F0); give only one")
    with pytest.raises(mdrmap.InvalidInput) as e:
        mdrmap.simulate(FN=-1, **LOAD)
    assert e.value.option == "FN" and "must be a finite number > 0" in e.value.message


def study(exe, ini, out, *args, check=True):
    p = subprocess.run([exe, "study", "--quiet", "--config", str(ini), "--output", str(out)]
                       + list(args), capture_output=True, text=True, env=ENV, timeout=300)
    if check:
        assert p.returncode == 0, p.stderr
    return p


GRID = "[grid]\n{load}R = 1\ntau = 1\nv = 0.1\n[history]\nw1_over_v = 10\nT1_over_tau = 2\n" \
       "[run]\nsamples = 5\n"
LOADS = [1e-3, 2e-3]


def read_map(path):
    with H5PY.File(path, "r") as f:
        return {k: f[k][()] for k in ("cases/F0", "results/FN_pre", "results/mu_pre")}, \
            sorted(f["cases"]), sorted(f["grid"]) if "grid" in f else None, \
            f["schema/cases/F0"].attrs["meaning"]


def test_every_spelling_gives_a_map_with_cases_f0(exe, tmp_path):
    grid_f0 = tmp_path / "f0.ini"
    grid_f0.write_text(GRID.format(load="F0 = 1e-3, 2e-3\n"))
    grid_fn = tmp_path / "fn.ini"
    grid_fn.write_text(GRID.format(load="FN = 1e-3, 2e-3\n"))
    no_load = tmp_path / "none.ini"
    no_load.write_text(GRID.format(load=""))
    csv = tmp_path / "cases.csv"
    csv.write_text("FN,R,tau,v,w1,T1\n" + "".join(f"{x},1,1,0.1,1,2\n" for x in LOADS))
    listed = tmp_path / "list.ini"
    listed.write_text("[cases]\nfile = cases.csv\n[run]\nsamples = 5\n")
    runs = {"F0 key": (grid_f0, []), "FN key": (grid_fn, []),
            "--F0": (no_load, ["--F0", "1e-3,2e-3"]), "--FN": (no_load, ["--FN", "1e-3,2e-3"]),
            "--set grid.FN": (no_load, ["--set", "grid.FN=1e-3,2e-3"]),
            "case list column FN": (listed, [])}
    maps = {}
    for label, (ini, args) in runs.items():
        out = tmp_path / (label.replace(" ", "_").replace("-", "") + ".h5")
        study(exe, ini, out, *args)
        values, cases, grid, meaning = read_map(out)
        assert "F0" in cases and "FN" not in cases, label
        assert grid is None if label.startswith("case list") else ("F0" in grid and
                                                                   "FN" not in grid), label
        assert "prescribed normal load" in (meaning.decode() if isinstance(meaning, bytes)
                                            else meaning), label
        assert list(values["cases/F0"]) == LOADS, label
        # the measured force before t = 0 is the prescribed load
        assert np.allclose(values["results/FN_pre"], LOADS, rtol=1e-9, atol=0), label
        maps[label] = values
    for label, values in maps.items():
        assert np.array_equal(values["results/mu_pre"], maps["F0 key"]["results/mu_pre"]), label
    # both spellings at once: one line, no map
    p = study(exe, no_load, tmp_path / "both2.h5", "--F0", "1e-3", "--FN", "1e-3", check=False)
    assert p.returncode == 2 and p.stderr.count("\n") == 1, p.stderr
    assert "--F0 and --FN are the same parameter" in p.stderr
    assert not (tmp_path / "both2.h5").exists()


def make_old(path):
    """Turns a load map of today into one as an mdrmap before the rename wrote
    it: /cases/FN, /grid/FN, /schema/cases/FN and `FN = ...` in the stored
    study; its last case pending, for a resume to run."""
    with H5PY.File(path, "r+") as f:
        f.move("cases/F0", "cases/FN")
        f.move("schema/cases/F0", "schema/cases/FN")
        f.move("grid/F0", "grid/FN")
        f.move("schema/grid/F0", "schema/grid/FN")
        axes = f["grid"].attrs["axes"]
        axes = axes.decode() if isinstance(axes, bytes) else str(axes)
        f["grid"].attrs["axes"] = axes.replace("F0", "FN")
        canon = f["provenance/config_canonical"]
        text = canon[()].tobytes()
        assert b"\nF0 = " in text
        canon[...] = np.frombuffer(text.replace(b"\nF0 = ", b"\nFN = "), dtype=np.uint8)
        status = f["results/status"]
        status[-1] = 0


def test_an_old_map_with_cases_fn_resumes_and_reads_as_f0(exe, tmp_path):
    for spelling in ("F0", "FN"):
        ini = tmp_path / f"{spelling}.ini"
        ini.write_text(GRID.format(load=f"{spelling} = 1e-3, 2e-3\n"))
        old = tmp_path / f"old_{spelling}.h5"
        study(exe, ini, old)
        with H5PY.File(old, "r") as f:
            want = f["results/mu_pre"][()]
        make_old(old)
        p = study(exe, ini, old, "--resume", check=False)
        assert p.returncode == 0, p.stderr
        with H5PY.File(old, "r") as f:
            assert list(f["results/status"][()]) == [1, 1]
            assert "FN" in f["cases"] and "F0" not in f["cases"]  # kept as written
            assert np.array_equal(f["results/mu_pre"][()], want)
        # another study is still refused
        other = tmp_path / "other.ini"
        other.write_text(GRID.format(load="F0 = 1e-3, 3e-3\n"))
        with H5PY.File(old, "r+") as f:
            f["results/status"][-1] = 0
        p = study(exe, other, old, "--resume", check=False)
        assert p.returncode == 2 and p.stderr.count("\n") == 1, p.stderr
        assert "(stored 'F0 = 0.001, 0.002', now 'F0 = 0.001, 0.003" in p.stderr, p.stderr
    # the Python reader names the old map's load F0
    ds = mdrmap.open_map(str(old))
    try:
        assert "F0" in ds.coords and "FN" not in ds.variables
        assert ds.attrs["grid_axes"].split(",")[0] == "F0"
        g = mdrmap.to_grid(ds)
        assert list(g["F0"].values) == [1e-3, 2e-3]
    finally:
        ds.close()


def test_tools_read_an_old_csv_case_line(exe, srcdir, tmp_path):
    from mdrmap.tools import _runs
    out = tmp_path / "new.csv"
    p = subprocess.run([exe, "simulate", "--F0", "0.1", "--R", "10", "--tau", "1", "--v", "1",
                        "--v1", "0.5", "--samples", "5", "--output", str(out)],
                       capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    text = out.read_text()
    assert "\n# case F0=0.10000000000000001 " in text
    old = tmp_path / "old.csv"
    old.write_text(text.replace("\n# case F0=", "\n# case FN="))
    for path in (out, old):
        run = _runs.read_csv(str(path), np)
        assert run.case["F0"] == 0.1 and "FN" not in run.case
        assert run.load and run.col["FN"].shape == (5,)


TWO_CASES = "[grid]\nd = 1e-3\nR = 1\ntau = 1\nv = 1, 2\nv1_over_v = 0.5\n" \
            "[run]\nsamples = 5\nrtol = 1e-3\nsolver = {solver}\n"


def old_solver_map(exe, tmp_path, old):
    """A map of the row whose stored study names the solver `old`, as an
    earlier mdrmap wrote it, its second case pending."""
    ini = tmp_path / "row.ini"
    ini.write_text(TWO_CASES.format(solver="row"))
    out = tmp_path / f"{old}.h5"
    study(exe, ini, out)
    with H5PY.File(out, "r+") as f:
        text = bytes(f["provenance/config_canonical"][()]).decode()
        assert "solver = row\n" in text
        del f["provenance/config_canonical"]
        f["provenance/config_canonical"] = np.frombuffer(
            text.replace("solver = row\n", f"solver = {old}\n").encode(), np.uint8)
        status = f["results/status"][()]
        status[1] = 0
        f["results/status"][...] = status
    return ini, out


def test_a_map_of_the_spectrum_solver_resumes_as_row(exe, tmp_path):
    """spectrum, the row's old name: its map resumes under either name."""
    ini, out = old_solver_map(exe, tmp_path, "spectrum")
    old_ini = tmp_path / "spectrum.ini"
    old_ini.write_text(TWO_CASES.format(solver="spectrum"))
    for config in (ini, old_ini):
        study(exe, config, out, "--resume")
        with H5PY.File(out, "r") as f:
            assert list(f["results/status"][()]) == [1, 1]


def test_a_map_of_the_retired_mdr_is_refused_in_one_line(exe, tmp_path):
    """mdr was retired: --resume of its map refuses in one line, the map untouched."""
    ini, out = old_solver_map(exe, tmp_path, "mdr")
    before = out.read_bytes()
    p = study(exe, ini, out, "--resume", check=False)
    assert p.returncode == 2, p.stderr
    assert p.stderr.count("\n") == 1, p.stderr
    assert "was written with solver mdr, which was retired" in p.stderr
    assert out.read_bytes() == before
    old_ini = tmp_path / "mdr.ini"
    old_ini.write_text(TWO_CASES.format(solver="mdr"))
    p = study(exe, old_ini, out, "--resume", check=False)
    assert p.returncode == 2 and "mdr was retired: use row" in p.stderr, p.stderr
