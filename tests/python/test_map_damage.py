"""Issue 32: mdrmap.open_map on a damaged map or a special file returns or
raises MapError, never waits for ever. A small map with 32 bytes inverted at
some offsets makes HDF5 loop for ever in xarray's h5netcdf (a dimension
scale's list; h5py's len(dataset.dims[i]) loops the same way) or crash; a
FIFO would wait for a writer. Each open runs in a child process with a hard
limit, so that the old behaviour fails the test instead of hanging it. (Which
offsets hang depends on the map's layout; at the time of writing 4096, 4112
and 5120 of this map hang, 1024 crashes h5py.)"""
import os
import shutil
import subprocess
import sys

import pytest

import mdrmap

TINY = """[grid]
d = 1e-3
R = 1
tau = 1
v = 1, 2
v1_over_v = 0.5
[run]
samples = 5
"""
OFFSETS = [0, 1024, 4096, 4112, 5120]
TIMEOUT = 5  # open_map's limit for the check of the map's structure


@pytest.fixture(scope="module")
def tiny_map(exe, tmp_path_factory):
    d = tmp_path_factory.mktemp("damage")
    (d / "tiny.ini").write_text(TINY)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run([exe, "study", "--quiet", "--config", str(d / "tiny.ini"), "--output",
                        str(d / "tiny.h5")], capture_output=True, text=True, env=env, timeout=300)
    assert p.returncode == 0, p.stderr
    return d / "tiny.h5"


def opened(paths, limit):
    """open_map on each path in a child process: one line per path, 'ok' or
    'MapError: ...'; the child is killed after `limit` seconds."""
    code = ("import sys, mdrmap\n"
            "for p in sys.argv[1:]:\n"
            "    try:\n"
            f"        mdrmap.open_map(p, timeout={TIMEOUT}).close(); print('ok', flush=True)\n"
            "    except mdrmap.MapError as e:\n"
            "        print('MapError:', e, flush=True)\n")
    try:
        p = subprocess.run([sys.executable, "-c", code] + [str(x) for x in paths],
                           capture_output=True, text=True, timeout=limit)
    except subprocess.TimeoutExpired as e:
        done = (e.stdout or b"").decode() if isinstance(e.stdout, bytes) else (e.stdout or "")
        pytest.fail(f"open_map did not return within {limit} s; done: {done!r}")
    assert p.returncode == 0, p.stderr
    return p.stdout.splitlines()


def test_damaged_maps_raise_or_open(tiny_map, tmp_path):
    paths = []
    for off in OFFSETS:
        path = tmp_path / f"inverted_{off}.h5"
        shutil.copyfile(tiny_map, path)
        with open(path, "r+b") as f:
            f.seek(off)
            b = f.read(32)
            f.seek(off)
            f.write(bytes(x ^ 0xFF for x in b))
        paths.append(path)
    lines = opened(paths, limit=len(paths) * (TIMEOUT + 10) + 20)
    assert len(lines) == len(paths), lines
    for off, line in zip(OFFSETS, lines):
        assert line == "ok" or line.startswith("MapError: "), (off, line)
        assert "\n" not in line
    # the signature's 8 bytes are gone at 0
    assert "no HDF5 signature" in lines[0], lines[0]


def test_special_files_are_refused(tmp_path):
    fifo = tmp_path / "map.fifo"
    os.mkfifo(fifo)
    lines = opened([fifo, "/dev/zero", tmp_path], limit=60)
    assert lines[0] == f"MapError: {fifo} is a FIFO, not an mdrmap map (a map is a regular file)"
    assert "is a character device" in lines[1] and "is a directory" in lines[2], lines


def test_a_structure_check_that_does_not_end_is_a_map_error(tiny_map, monkeypatch):
    """The limit itself, whatever the layout: a check that never ends."""
    monkeypatch.setattr(mdrmap.maps, "_CHECK_SCRIPT", "import time\ntime.sleep(60)\n")
    with pytest.raises(mdrmap.MapError, match="did not end within 1 s: a damaged map"):
        mdrmap.open_map(str(tiny_map), timeout=1)


def test_open_map_takes_a_path_only(tiny_map):
    import pathlib

    ds = mdrmap.open_map(pathlib.Path(tiny_map))
    ds.close()
    with pytest.raises(mdrmap.MapError, match="needs the path of a map"):
        mdrmap.open_map(None)
