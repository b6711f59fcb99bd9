"""mdrmap.fit: the worked example's records (jobs/examples/fit_load_*.csv,
made by mdrmap simulate at R 10, aT 2 under the load 0.1 with ~1% noise)
fitted from 3x off over threads: the truth inside the 95% intervals, and the
same numbers with 1 thread and 2 (the CLI's library, the CLI's result)."""
import json
import os
import subprocess
import sys

import mdrmap

SRC = os.environ.get("MDRMAP_SRCDIR", os.path.join(os.path.dirname(__file__), "..", ".."))
DATA = [os.path.join(SRC, "jobs", "examples", f"fit_load_{n}.csv") for n in "ab"]
CASE = dict(F0=0.1, tau=1, R=30, aT=0.667)


def test_fit_recovers_the_truth_over_threads():
    one = mdrmap.fit(data=DATA, free="R,aT", threads=1, **CASE)
    two = mdrmap.fit(data=DATA, free=["R", "aT"], threads=2, **CASE)
    three = mdrmap.fit(data=DATA, free="R,aT", starts=3, bounds={"R": (1, 100)}, **CASE)
    for name, truth in (("R", 10.0), ("aT", 2.0)):
        lo, hi = one["parameters"][name]["ci95"]
        assert lo <= truth <= hi
        assert two["parameters"][name] == one["parameters"][name]
        lo, hi = three["parameters"][name]["ci95"]
        assert lo <= truth <= hi
    assert one["undetermined"] == []
    assert one["evaluations"] == two["evaluations"] < three["evaluations"]


def test_fit_matches_the_command_line(tmp_path):
    out = tmp_path / "fit.json"
    args = [os.environ["MDRMAP_EXE"], "fit", "--free", "R,aT", "--output", str(out)]
    for d in DATA:
        args += ["--data", d]
    for k, v in CASE.items():
        args += [f"--{k}", str(v)]
    subprocess.run(args, check=True)
    cli = json.loads(out.read_text())
    py = mdrmap.fit(data=DATA, free="R,aT", **CASE)
    for name in ("R", "aT"):
        assert py["parameters"][name]["value"] == cli["parameters"][name]["value"]


def test_fit_refuses_a_free_parameter_the_case_has_not():
    try:
        mdrmap.fit(data=DATA, free="beta", **CASE)
    except mdrmap.InvalidInput as e:
        assert e.option == "free" and "beta" in str(e)
    else:
        raise AssertionError("beta on a parabola was accepted")


def test_plot_fit_draws_the_records_of_the_json(tmp_path):
    out = tmp_path / "fit.json"
    args = [os.environ["MDRMAP_EXE"], "fit", "--free", "R,aT", "--output", str(out)]
    for d in DATA:
        args += ["--data", d]
    for k, v in CASE.items():
        args += [f"--{k}", str(v)]
    subprocess.run(args, check=True)
    records = json.loads(out.read_text())["records"]
    assert [len(r["columns"]["mu"]["model"]) for r in records] == [len(r["t"]) for r in records]
    run = [sys.executable, "-m", "mdrmap", "plot_fit"]
    p = subprocess.run(run + [str(out), "-o", str(tmp_path / "fit.png")], capture_output=True,
                       text=True)
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "fit.png").stat().st_size > 0
    (tmp_path / "bad.json").write_text("{}")
    p = subprocess.run(run + [str(tmp_path / "bad.json"), "-o", str(tmp_path / "b.png")],
                       capture_output=True, text=True)
    assert p.returncode == 2 and "no records" in p.stderr and len(p.stderr.splitlines()) == 1
    assert not (tmp_path / "b.png").exists()
