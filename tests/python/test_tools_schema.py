"""The map tools (python -m mdrmap TOOL) take scales, case columns and units from the map
(/scales, /schema), not from their own lists or formulas: on a copy of an
example map whose /scales/length is doubled, whose /schema relabels a unit
and drops a case column, their output changes accordingly; a map without
/scales (or /schema) is refused in one line naming the group; the history
tools (steps.py, healing.py) measure by the scales mdrmap gives for the
case; and no tool source holds a Hertz-scale formula. Each test fails on
the tools before they read /scales (checked against commit cbc06d0's)."""
import os
import re
import shutil
import subprocess
import sys

import pytest

h5py = pytest.importorskip("h5py")
pytest.importorskip("matplotlib")

# every tool that reads a map, with the arguments it needs on velocity_steps.h5
MAP_TOOLS = {
    "map_summary": ["--no-config"],
    "map_steps": [],
    "map_rate_state": ["--event", "0"],
    "map_friction_velocity": [],
    "map_healing": [],
    "plot_map": [],
    "plot_timeseries": [],
}
# the Hertz scales written out (the cube root of the load, the root of R d, the 16/3 of Hertz)
FORMULAS = re.compile(r"cbrt|\*\* *\( *1 */ *3 *\)|16 */ *3|sqrt\( *R\b|16 *\* *G")


@pytest.fixture(scope="module")
def maps(exe, srcdir, tmp_path_factory):
    """(the map of jobs/examples/velocity_steps.ini, its altered copy, a copy
    without /scales, a copy without /schema)."""
    work = tmp_path_factory.mktemp("tools_schema")
    orig = str(work / "steps.h5")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run([exe, "study", "--quiet", "--config",
                        f"{srcdir}/jobs/examples/velocity_steps.ini", "--output", orig],
                       capture_output=True, text=True, env=env, timeout=300)
    assert p.returncode == 0, p.stderr
    altered, noscales, noschema = (str(work / n) for n in ("altered.h5", "noscales.h5",
                                                            "noschema.h5"))
    for path in (altered, noscales, noschema):
        shutil.copy(orig, path)
    with h5py.File(altered, "r+") as f:
        f["scales/length"][...] = 2 * f["scales/length"][()]
        f["schema/results/FN_pre"].attrs["unit"] = "kN"
        del f["schema/cases/G"]  # a column the map does not list is not a case parameter
    with h5py.File(noscales, "r+") as f:
        del f["scales"]
    with h5py.File(noschema, "r+") as f:
        del f["schema"]
    return orig, altered, noscales, noschema


def tool(srcdir, name, *args, code=0):
    p = subprocess.run([sys.executable, "-m", "mdrmap", name, *args],
                       capture_output=True, text=True, timeout=300)
    assert p.returncode == code, f"{name} {args}: exit {p.returncode}\n{p.stdout}\n{p.stderr}"
    return p.stdout, p.stderr


def stats(out, label):
    """min, median, max of the map_summary row that starts with `label`."""
    for line in out.splitlines():
        if line.strip().startswith(label):
            return [float(x) for x in line.split()[-3:]]
    raise AssertionError(f"no row {label!r} in\n{out}")


def test_summary_reads_scales_units_and_columns(maps, srcdir, tmp_path):
    orig, altered = maps[:2]
    out = {}
    for name, path in (("orig", orig), ("altered", altered)):
        out[name], _ = tool(srcdir, "map_summary", path, "--no-config", "--csv",
                            str(tmp_path / f"{name}.csv"))
    # units from /schema
    assert "FN_pre [force]" in out["orig"] and "FN_pre [kN]" in out["altered"]
    # lengths over /scales/length (D_c), zeta0 = v tau over it; friction scale untouched
    for k in (0, 1):
        d0, d1 = stats(out["orig"], f"event {k}: D_c / a0"), stats(out["altered"], f"event {k}: D_c / a0")
        assert d1 == pytest.approx([x / 2 for x in d0], rel=1e-2)
        assert stats(out["orig"], f"event {k}: a / a0/R") == stats(out["altered"], f"event {k}: a / a0/R")
    zeta = [re.search(r"zeta0 = .*\)  (\S+) \.\. (\S+)", out[n]).groups() for n in ("orig", "altered")]
    assert [float(x) / 2 for x in zeta[0]] == pytest.approx([float(x) for x in zeta[1]], rel=1e-2)
    # the case columns are those /schema lists
    heads = {n: (tmp_path / f"{n}.csv").read_text().splitlines()[0].split(",") for n in out}
    assert "G" in heads["orig"] and "G" not in heads["altered"]
    assert "scale_length" in heads["orig"]


def rows(out, ncol):
    """The numeric table rows of map_steps (ncol columns)."""
    return [[float(x) for x in ln.split()] for ln in out.splitlines()
            if ln.split() and ln.split()[0].isdigit() and len(ln.split()) == ncol]


def test_steps_and_rate_state_follow_the_scales(maps, srcdir, tmp_path):
    orig, altered = maps[:2]
    a, _ = tool(srcdir, "map_steps", orig, "-o", str(tmp_path / "a.png"))
    b, _ = tool(srcdir, "map_steps", altered, "-o", str(tmp_path / "b.png"))
    ra, rb = rows(a, 9), rows(b, 9)
    assert len(ra) == len(rb) == 9
    for x, y in zip(ra, rb):  # case zeta0 ratio before after mu_after norm0 norm_end D_c
        assert y[1] == pytest.approx(x[1] / 2, rel=1e-3)  # zeta0
        assert y[8] == pytest.approx(x[8] / 2, rel=1e-3)  # D_c / a0
        assert y[3:6] == x[3:6]  # mu / (a0/R): /scales/friction is unchanged
    a, _ = tool(srcdir, "map_rate_state", orig, "-o", str(tmp_path / "c.png"))
    b, _ = tool(srcdir, "map_rate_state", altered, "-o", str(tmp_path / "d.png"))
    line = {n: {ln.split()[0]: ln.split() for ln in o.splitlines() if ln.split()}
            for n, o in (("a", a), ("b", b))}
    assert [float(x) / 2 for x in line["a"]["D_c"][-3:]] == \
        pytest.approx([float(x) for x in line["b"]["D_c"][-3:]], rel=1e-3)
    assert line["a"]["a"][-3:] == line["b"]["a"][-3:]


@pytest.mark.parametrize("name", sorted(MAP_TOOLS))
def test_map_without_scales_or_schema_is_refused(maps, srcdir, tmp_path, name):
    for path, group in ((maps[2], "scales"), (maps[3], "schema")):
        png = tmp_path / "x.png"
        args = [path] + MAP_TOOLS[name] + ([] if name == "map_summary" else ["-o", str(png)])
        _, err = tool(srcdir, name, *args, code=2)
        assert err.count("\n") == 1 and f"has no /{group} group" in err, err
        assert not png.exists()


def test_no_tool_recomputes_a_hertz_scale(srcdir):
    found = []
    roots = [os.path.join(srcdir, "tools"), os.path.join(srcdir, "tools", "maps"),
             os.path.join(srcdir, "src", "python", "mdrmap"),
             os.path.join(srcdir, "src", "python", "mdrmap", "tools")]
    for root in roots:
        for name in sorted(os.listdir(root)):
            if not name.endswith(".py"):
                continue
            with open(os.path.join(root, name), encoding="utf-8") as f:
                for k, line in enumerate(f, 1):
                    if FORMULAS.search(line):
                        found.append(f"{root}/{name}:{k}: {line.strip()}")
    assert not found, "Hertz scales written out (read the map's /scales instead):\n" + \
        "\n".join(found)


def test_history_tools_take_the_scales_mdrmap_gives(exe, srcdir, tmp_path):
    """python -m mdrmap steps measures by the case's scales from mdrmap (each
    run's Result.scales, kept as the `# scales` line of the CSVs), not by a
    formula: doubling the length and friction scales there halves D_c and mu
    of the table read back."""
    args = ["--d", "0.01", "--R", "100", "--samples", "21", "--zeta0", "1", "--csv-dir",
            str(tmp_path)]
    first, _ = tool(srcdir, "steps", *args)
    csvs = sorted(tmp_path.glob("step_*.csv"))
    assert len(csvs) == 2
    for path in csvs:
        lines = path.read_text().splitlines(True)
        k = next(i for i, ln in enumerate(lines) if ln.startswith("# scales "))
        fields = dict(t.split("=", 1) for t in lines[k].split()[2:])
        assert "length" in fields and "friction" in fields
        for name in ("length", "friction"):
            fields[name] = repr(2 * float(fields[name]))
        lines[k] = "# scales " + " ".join(f"{n}={v}" for n, v in fields.items()) + "\n"
        path.write_text("".join(lines))
    again, _ = tool(srcdir, "steps", *args, "--from-csv")
    table = {n: [ln.split() for ln in o.splitlines() if ln.startswith("1 ")]
             for n, o in (("first", first), ("again", again))}
    assert len(table["first"]) == len(table["again"]) == 2  # the step up and down
    for x, y in zip(table["first"], table["again"]):
        # zeta0 step mu_pre jump mu_end D_c a a-b b d_end settle
        for col in (2, 3, 4, 5):
            if x[col] != "nan":
                assert float(y[col]) == pytest.approx(float(x[col]) / 2, rel=1e-3)
