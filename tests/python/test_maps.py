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
        # the axes of more than one value are the dimensions, the others scalars
        varied = [a for a in axes if len(ds.attrs[f"grid_{a}"]) > 1]
        assert g["mu_after"].dims == tuple(varied) + ("event",)
        for a in set(axes) - set(varied):
            assert g[a].ndim == 0 and float(g[a]) == ds.attrs[f"grid_{a}"][0]
        assert list(g["tau"].values) == [0.5, 2.0] and g.sizes["v"] == 5
        # a point of the grid is the case mdrmap.simulate computes
        assert float(g["d"]) == 1e-3 and float(g["R"]) == 1  # one value each: scalars
        pt = g.sel(tau=2.0, v=1.0, v1_over_v=0.5)
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


def study_map(exe, config_text, path):
    """Runs `mdrmap study` (one MPI process) on `config_text`; the map's path."""
    ini = path.with_suffix(".ini")
    ini.write_text(config_text)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run([exe, "study", "--quiet", "--config", str(ini), "--output", str(path)],
                       capture_output=True, text=True, env=env, timeout=300)
    assert p.returncode == 0, p.stderr
    return str(path)


def test_to_grid_spectrum_is_one_material_axis(exe, tmp_path):
    """Issue 32: a 32-term spectrum is 64 grid axes (68 with d, R, tau, G, v,
    ...), past numpy's dimensions; to_grid makes the axes of one value scalar
    coordinates and the spectrum's varied terms one dimension `material`."""
    lines = ["[grid]", "d = 1e-3", "R = 1", "tau = 0", "G = 1", "G1 = 1, 2", "tau1 = 0.01"]
    for k in range(2, 33):
        tau = "1, 10" if k == 2 else f"{10.0 ** (k / 4 - 2):g}"
        lines += [f"G{k} = 1", f"tau{k} = {tau}"]
    lines += ["v = 0.1, 1", "v1_over_v = 2", "[run]", "samples = 5", "rtol = 1e-3"]
    path = study_map(exe, "\n".join(lines) + "\n", tmp_path / "spectrum.h5")
    ds = mdrmap.open_map(path)
    try:
        assert len(ds.attrs["grid_axes"].split(",")) > 64
        g = mdrmap.to_grid(ds)
        assert g["mu_after"].dims == ("material", "v", "event")
        assert dict(g.sizes) == {"material": 4, "v": 2, "event": 1}
        # the varied terms along `material` (C order: G1 slower than tau2)
        assert list(g["G1"].values) == [1, 1, 2, 2] and g["G1"].dims == ("material",)
        assert list(g["tau2"].values) == [1, 10, 1, 10]
        assert g["G5"].ndim == 0 and float(g["G5"]) == 1.0
        assert float(g["tau32"]) == ds.attrs["grid_tau32"][0]
        # each grid point is its row
        for m in range(4):
            for j in range(2):
                pt = g.isel(material=m, v=j)
                row = ds.isel(case=int(pt["case"]))
                for key in ("G1", "tau2", "v"):
                    assert float(row[key]) == float(pt[key])
                assert float(row["mu_after"][0]) == float(pt["mu_after"][0])
    finally:
        ds.close()


def test_to_grid_needs_a_dataset():
    for bad in (None, "map.h5", 3):
        with pytest.raises(mdrmap.MapError, match="needs the Dataset of open_map"):
            mdrmap.to_grid(bad)
