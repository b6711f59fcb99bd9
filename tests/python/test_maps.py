"""mdrmap.open_map / to_grid on an example study's map (jobs/examples/quick.ini,
run here by `mdrmap study` in one MPI process), and their errors."""
import os
import subprocess

import pytest

import mdrmap


@pytest.fixture(scope="module")
def quick_map(exe, srcdir, tmp_path_factory):
    path = str(tmp_path_factory.mktemp("maps") / "quick.h5")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run([exe, "study", "--quiet", "--config",
                        f"{srcdir}/jobs/examples/quick.ini", "--output", path],
                       capture_output=True, text=True, env=env, timeout=300)
    assert p.returncode == 0, p.stderr
    return path


def test_open_map_and_to_grid(quick_map):
    ds = mdrmap.open_map(quick_map)
    try:
        assert ds.sizes["case"] == 40 and ds.sizes["event"] == 1
        axes = ds.attrs["grid_axes"].split(",")
        assert {"d", "R", "tau", "v", "v1_over_v"} <= set(axes)
        g = mdrmap.to_grid(ds)
        assert g["mu_after"].dims == tuple(axes) + ("event",)
        assert list(g["tau"].values) == [0.5, 2.0] and g.sizes["v"] == 5
        # a point of the grid is the case mdrmap.simulate computes
        pt = g.sel(d=1e-3, R=1, tau=2.0, v=1.0, v1_over_v=0.5)
        r = mdrmap.simulate(d=1e-3, R=1, tau=2, v=1, v1=0.5, t_end=12, samples=101)
        assert float(pt["mu_after"].values.ravel()[0]) == pytest.approx(
            r.events[0]["mu_after"], rel=1e-12)
        assert float(pt["mu_peak"].values.ravel()[0]) == pytest.approx(
            r.events[0]["mu_peak"], rel=1e-12)
    finally:
        ds.close()


def test_map_errors(tmp_path, quick_map):
    with pytest.raises(mdrmap.MapError, match="no such file"):
        mdrmap.open_map(str(tmp_path / "absent.h5"))
    (tmp_path / "x.h5").write_text("not hdf5")
    with pytest.raises(mdrmap.MapError, match="not a readable HDF5 file"):
        mdrmap.open_map(str(tmp_path / "x.h5"))
    assert issubclass(mdrmap.MapError, ValueError)
    ds = mdrmap.open_map(quick_map)
    try:
        del ds.attrs["grid_axes"]
        with pytest.raises(mdrmap.MapError, match="not a grid study"):
            mdrmap.to_grid(ds)
    finally:
        ds.close()
