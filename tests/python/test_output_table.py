"""The output table (src/core/outputs/output_table.cpp): every output
quantity has one name, the same in the CSV of `mdrmap simulate`, the Python
result, the map of `mdrmap study` (its datasets and /schema) and the
generated reference docs/reference/map-schema.md; and nothing those outputs
hold lacks an entry. Maps written with an old name (events/d_c) read under
today's name, and --resume refuses them in one line."""
import os
import re
import subprocess
import sys

import pytest

import mdrmap
from mdrmap import _core

H5PY = pytest.importorskip("h5py")
ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
TABLE = _core.output_table()
# a load case with a hold: every event metric, defined or not (D_c_undefined)
LOAD = ["--F0", "0.1", "--R", "10", "--tau", "1", "--v", "1", "--history", "0.5:3,0:2,1:3",
        "--samples", "4"]
# the provenance of the CSV's first line besides the table's results
PROVENANCE = {"solver", "rtol"}
INFO_EXTRA = {"solver", "rtol", "version", "commit", "error_vs_exact", "error_vs_reference",
              "reference", "reference_rtol"}


def names(group, where, load=True):
    return [o["name"] for o in TABLE if o["group"] == group and o[where]
            and (load or not o["load_only"])]


def states(load=True):
    return [o["name"] for o in TABLE if o["group"] == "series" and o["name"] not in
            ("t", "segment") and (load or not o["load_only"])]


def event_names(where, load=True):
    """The event names of `where` in table order: metrics, and each state
    quantity at each instant (the CSV: mu only)."""
    out = []
    for o in TABLE:
        if not o[where]:
            continue
        if o["group"] == "event":
            out.append(o["name"])
        if o["group"] == "event_state":
            qs = ["mu"] if where == "csv" else states(load)
            out += [f"{q}_{o['name']}" for q in qs]
    return out


def test_the_table_names_each_quantity_once():
    seen = set()
    for o in TABLE:
        key = (o["group"] in ("series",), o["name"])
        assert key not in seen, o["name"]
        seen.add(key)
        assert o["meaning"] and o["unit"], o["name"]
    assert "D_c" in names("event", "map") and "d_c" not in names("event", "map")
    units = {o["unit"] for o in TABLE}
    assert "s" not in units  # units are dimension names (wall_seconds: wall-clock time)


def csv_lines(exe, args):
    p = subprocess.run([exe, "simulate"] + args, capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    return p.stdout.splitlines()


def keys(line, skip=()):
    return [kv.split("=", 1)[0] for kv in line.split()[1:] if "=" in kv and
            kv.split("=", 1)[0] not in skip]


def test_csv_and_python_spell_the_table(exe):
    lines = csv_lines(exe, LOAD)
    first = lines[0].split(") simulate ", 1)[1]
    assert [k for k in keys("x " + first) if k not in PROVENANCE] == names("result", "csv")
    events = [ln for ln in lines if ln.startswith("# event ")]
    assert len(events) == 3
    for ln in events:
        assert keys(ln[1:], ("k", "D_c_undefined")) == event_names("csv"), ln
    assert any("D_c_undefined=hold" in ln for ln in events)
    scales = next(ln for ln in lines if ln.startswith("# scales "))
    assert keys(scales[1:]) == names("scale", "csv")
    pre = next(ln for ln in lines if ln.startswith("# pre "))
    assert keys(pre[1:]) == states()
    header = next(ln for ln in lines if not ln.startswith("#"))
    assert header.split(",") == names("series", "csv")
    depth = csv_lines(exe, ["--d", "0.1"] + LOAD[2:])
    assert next(ln for ln in depth if not ln.startswith("#")).split(",") == \
        names("series", "csv", load=False)

    r = mdrmap.simulate(F0=0.1, R=10, tau=1, v=1, history=[(0.5, 3), (0, 2), (1, 3)], samples=4)
    for e in r.events:
        assert [k for k in e if k not in ("k", "D_c_undefined")] == event_names("csv")
    assert list(r.pre) == states()
    assert list(r.scales) == names("scale", "csv")
    assert r.columns == names("series", "csv")
    for name in r.columns:
        assert getattr(r, name).shape == r.t.shape
    assert [k for k in r.info if k not in INFO_EXTRA] == names("result", "csv")


def study(exe, tmp_path, name, *args):
    ini = tmp_path / f"{name}.ini"
    ini.write_text("[grid]\nF0 = 1e-3\nR = 1\ntau = 1\nv = 0.1, 1\n[history]\n"
                   "w1_over_v = 10\nT1_over_tau = 2\n[run]\nsamples = 5\ntimeseries = true\n")
    out = tmp_path / f"{name}.h5"
    p = subprocess.run([exe, "study", "--quiet", "--config", str(ini), "--output", str(out)]
                       + list(args), capture_output=True, text=True, env=ENV, timeout=300)
    return ini, out, p


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def test_the_map_spells_the_table(exe, tmp_path):
    _, out, p = study(exe, tmp_path, "m")
    assert p.returncode == 0, p.stderr
    with H5PY.File(out, "r") as f:
        assert sorted(f["events"]) == sorted(event_names("map"))
        results = set(f["results"]) - {"status"} - {f"{q}_pre" for q in states()}
        assert results == set(names("result", "map"))
        assert set(f["timeseries"]) == set(names("series", "map"))
        assert set(f["scales"]) == set(names("scale", "map"))
        unit = {o["name"]: o["unit"] for o in TABLE if o["group"] != "event_state"}
        meaning = {o["name"]: o["meaning"] for o in TABLE if o["group"] == "event"}
        for group, kind in (("events", "event"), ("results", "result"), ("scales", "scale")):
            for name in names(kind, "map"):
                assert text(f[f"{group}/{name}"].attrs["units"]) == unit[name], name
                assert text(f[f"schema/{group}/{name}"].attrs["unit"]) == unit[name], name
        for name, m in meaning.items():
            if name in f["events"]:
                assert text(f[f"schema/events/{name}"].attrs["meaning"]) == m, name
    ds = mdrmap.open_map(str(out))
    try:
        for name in event_names("map") + names("result", "map"):
            assert name in ds.variables, name
        for name in names("scale", "map"):
            assert "scale_" + name in ds.variables, name
    finally:
        ds.close()


def test_the_reference_page_lists_the_table(srcdir):
    with open(os.path.join(srcdir, "docs", "reference", "map-schema.md")) as f:
        page = f.read()
    section = page.split("## Output quantities", 1)[1].split("\n## ", 1)[0]
    rows = re.findall(r"^\| `([^`]+)` \|", section, re.M)
    assert rows == [f"<q>_{o['name']}" if o["group"] == "event_state" else o["name"]
                    for o in TABLE]
    for name in event_names("map", load=True):
        assert f"| `/events/{name}` |" in page, name
    for o in TABLE:
        if o["old_map_name"]:
            assert f"`/events/{o['old_map_name']}` (now `{o['name']}`)" in section


def make_old(path):
    """A map as an mdrmap before the output table wrote it: /events/d_c."""
    with H5PY.File(path, "r+") as f:
        for o in TABLE:
            if o["old_map_name"]:
                f.move(f"events/{o['name']}", f"events/{o['old_map_name']}")
                f.move(f"schema/events/{o['name']}", f"schema/events/{o['old_map_name']}")
        f["results/status"][-1] = 0


def test_an_old_map_reads_under_todays_names_and_is_not_resumed(exe, srcdir, tmp_path):
    ini, out, p = study(exe, tmp_path, "old")
    assert p.returncode == 0, p.stderr
    with H5PY.File(out, "r") as f:
        want = f["events/D_c"][()]
    make_old(out)
    ds = mdrmap.open_map(str(out))
    try:
        assert "D_c" in ds.variables and "d_c" not in ds.variables
        assert ds["D_c"].attrs["units"] == "length"
        assert ds["D_c"].fillna(-1).values.tolist() == \
            [[-1 if x > 1e36 else x for x in row] for row in want.tolist()]
    finally:
        ds.close()
    before = out.read_bytes()
    _, _, p = study(exe, tmp_path, "old", "--resume")
    assert p.returncode == 2 and p.stderr.count("\n") == 1, p.stderr
    assert "holds /events/d_c, the old name of /events/D_c" in p.stderr, p.stderr
    assert out.read_bytes() == before
    # the tools read it as D_c
    t = subprocess.run([sys.executable, "-m", "mdrmap", "map_summary", str(out),
                        "--no-config"], capture_output=True, text=True, env=ENV, timeout=300)
    assert t.returncode == 0, t.stderr
    assert "D_c / a0" in t.stdout
    c = subprocess.run([sys.executable, os.path.join(srcdir, "tools", "maps", "check_map.py"),
                        str(out), "--quiet"], capture_output=True, text=True, timeout=300)
    assert c.returncode == 0, c.stdout + c.stderr
