"""Maps of `mdrmap study` as xarray Datasets: open_map(path) and to_grid(ds).

open_map(path) merges the map's groups into one Dataset with dimension
`case` (and `event` for per-event values, `sample` for the time series). It
reads both layouts (the root attribute mdrmap_schema):

  - /cases columns as coordinates along `case` (mdrmap-map/2: d or F0, R, tau,
    G, v, and w and T over (case, event); mdrmap-map/1: d, R, tau, v, v1, G);
    the prescribed load of a map written before it was named F0 (/cases/FN,
    a grid axis FN) is read as F0 too (CASE_ALIASES);
  - /results under their bare names (FN_pre, error_estimate, wall_seconds,
    status; mdrmap-map/1 also mu_jump, mu_post, ...), and `message`: why a
    case failed ('' otherwise; mdrmap-map/2: from /failures/{case,message});
  - /events (mdrmap-map/2) under their bare names over (case, event): t,
    mu_after, mu_peak, a, b, a_minus_b, D_c, ...; undefined values (the netCDF
    fill value) are NaN; an old map's events/d_c is D_c (OLD_OUTPUT_NAMES);
  - /analytic as analytic_<name>, /residuals as residual_<name>, /scales as
    scale_<name> (the case's reference length, depth, force, friction and
    time), /timeseries as ts_<name> over (case, sample) (mdrmap-map/2: also ts_segment over
    sample, the segment of each sample);
  - each variable with the attributes units and long_name from the map's
    /schema (maps written before /schema have none) and map_path (its
    dataset in the map);
  - the Dataset's attributes: the map's root attributes (provenance) and, for
    a grid study, grid_axes (comma list), grid_shape, grid_log and
    grid_<axis> (the axis values).

Maps with dimension scales are opened lazily (xarray engine h5netcdf, the
file stays open until ds.close()); older maps too, their phony dimensions
renamed to case and sample.

to_grid(ds) reshapes every variable along `case` to the grid's axes of more
than one value (C order, last axis fastest: the case order of a [grid]
study), with the axis values as index coordinates; an axis of one value (a
fixed d, G, T1_over_tau, a spectrum's fixed terms) is a scalar coordinate;
a relaxation spectrum's varied terms (G1, tau1, ..., G32, tau32) are one
dimension `material` (their combinations in C order, each term a coordinate
along it), so a spectrum of 32 terms fits numpy's dimensions. The other
/cases columns (e.g. v1; w and T) are N-d coordinates, and a coordinate
`case` holds each point's row number in the map. It checks that the /cases
columns equal the grid (to 1e-12).

Both raise MapError (a ValueError, one line) for a file that is not a
readable map or a Dataset that is not a grid study's. open_map refuses what
is not a regular file with HDF5's signature (a FIFO, a device) at once, and
first reads the structure of every dataset it opens (dimension scales,
attributes, first element) with h5py in a child process, so that a damaged
map on which HDF5 loops for ever or crashes raises MapError (after
open_map's `timeout`, 60 s by default) instead of hanging the caller. Needs h5py, xarray and
h5netcdf (imported when called). python -m mdrmap mapxr is the command line of this
module.
"""

import math
import os
import re
import stat
import warnings

SCHEMA1 = "mdrmap-map/1"
SCHEMA2 = "mdrmap-map/2"
SCHEMAS = {SCHEMA1: 1, SCHEMA2: 2}
# /cases columns a schema-1 map must have
_CASE_COLS1 = ["d", "R", "tau", "v", "v1"]
# the old names of /cases columns and grid axes -> today's: FN, the prescribed
# normal load in maps written before it was named F0 (apart from the measured
# normal force FN of /results and /timeseries)
CASE_ALIASES = {"FN": "F0"}


def case_name(name):
    """Today's name of a /cases column or grid axis (F0 for an old map's FN)."""
    return CASE_ALIASES.get(name, name)


def _old_output_names():
    """{path: old path} of the output quantities whose name in maps changed
    (the output table's old_map_name: events/D_c was events/d_c)."""
    from . import _core

    group = {"event": "events", "event_state": "events", "result": "results"}
    return {f"{group[o['group']]}/{o['name']}": f"{group[o['group']]}/{o['old_map_name']}"
            for o in _core.output_table() if o["old_map_name"] and o["group"] in group}


# today's path -> its old path in maps written before the output table
OLD_OUTPUT_NAMES = _old_output_names()


class Renamed:
    """An open h5py File (or Group) of a map with old output names, that
    shows them under today's (OLD_OUTPUT_NAMES): f["events/D_c"] reads an old
    map's /events/d_c, the group /events lists D_c (and /schema/events so). Everything else is
    the h5py object's."""

    def __init__(self, node, h5py, prefix=""):
        self._node, self._h5py, self._prefix = node, h5py, prefix
        full = {p + new: p + old for new, old in OLD_OUTPUT_NAMES.items()
                for p in ("", "schema/") if p + old in node.file}  # and its /schema entry
        self._old = {n[len(prefix):]: o[len(prefix):] for n, o in full.items()
                     if n.startswith(prefix) and n not in node.file}

    def _real(self, key):
        return self._old.get(key.strip("/"), key)

    def __getitem__(self, key):
        obj = self._node[self._real(key)]
        if isinstance(obj, self._h5py.Group):
            return Renamed(obj, self._h5py, self._prefix + key.strip("/") + "/")
        return obj

    def __contains__(self, key):
        return self._real(key) in self._node

    def get(self, key, default=None):
        return self[key] if key in self else default

    def keys(self):
        back = {o: n for n, o in self._old.items() if "/" not in n}
        return [back.get(k, k) for k in self._node.keys()]

    def __iter__(self):
        return iter(self.keys())

    def __len__(self):
        return len(self._node)

    def items(self):
        return [(k, self[k]) for k in self.keys()]

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self._node.file.close()

    def __getattr__(self, name):
        return getattr(self._node, name)


class MapError(ValueError):
    """A file that is not a readable mdrmap map, or a map a function cannot use."""


class MapWarning(UserWarning):
    """A map of a schema this version does not know (read as the nearest one)."""


def text(value):
    """An HDF5 string attribute or a uint8 text dataset as str."""
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    dtype = getattr(value, "dtype", None)
    if dtype is not None and dtype.kind == "S":
        return value.tobytes().decode("utf-8", "replace")
    if dtype is not None and dtype.kind in "ui" and getattr(value, "ndim", 0) == 1:
        return bytes(value.astype("u1")).decode("utf-8", "replace")  # a text dataset
    return str(value)  # numbers (e.g. integer attributes) as they print


def schema_name(f):
    """The root attribute mdrmap_schema of an open map, as str."""
    return text(f.attrs["mdrmap_schema"]).rstrip("\0") if "mdrmap_schema" in f.attrs else ""


def schema_version(f):
    """1 or 2: the layout of an open map (an unknown name is judged by content)."""
    name = schema_name(f)
    if name in SCHEMAS:
        return SCHEMAS[name]
    return 2 if "events" in f or "cases/w" in f else 1


HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"


def _kind(mode):
    """What a file that is not a regular file is, for a message."""
    for test, name in ((stat.S_ISDIR, "a directory"), (stat.S_ISFIFO, "a FIFO"),
                       (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
                       (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return name
    return "not a regular file"


def check_file(path):
    """MapError (one line) unless `path` is a regular file with HDF5's
    signature (at byte 0, or after a user block of 512, 1024, 2048, ...
    bytes). A FIFO or a device is refused before it is opened: reading one
    would wait for a writer or never end."""
    try:
        st = os.stat(path)
    except FileNotFoundError:
        raise MapError(f"no such file: {path}") from None
    except OSError as e:
        raise MapError(f"cannot read {path} ({e.strerror})") from None
    if not stat.S_ISREG(st.st_mode):
        raise MapError(f"{path} is {_kind(st.st_mode)}, not an mdrmap map (a map is a regular "
                       f"file)")
    try:
        with open(path, "rb") as f:
            offset = 0
            while offset + len(HDF5_SIGNATURE) <= st.st_size:
                f.seek(offset)
                if f.read(len(HDF5_SIGNATURE)) == HDF5_SIGNATURE:
                    return
                offset = 512 if offset == 0 else 2 * offset
    except OSError as e:
        raise MapError(f"cannot read {path} ({e.strerror})") from None
    raise MapError(f"{path} is not a readable HDF5 file (no HDF5 signature)")


# Run in a child process by check_readable: opens the map with h5py and, for
# every dataset of the groups open_map reads (GROUPS), what xarray's h5netcdf
# reads of it (its dimension scales,
# its attributes, its first element). Exit 0, or 1 with the problem on stderr.
_CHECK_SCRIPT = r"""
import sys
import h5py
def visit(name, obj):
    if isinstance(obj, h5py.Dataset):
        [len(d) for d in obj.dims]
        [list(d.keys()) for d in obj.dims]
        dict(obj.attrs)
        if obj.size:
            obj[(0,) * obj.ndim] if obj.ndim else obj[()]
    else:
        dict(obj.attrs)
try:
    with h5py.File(sys.argv[1], "r") as f:
        dict(f.attrs)
        for group in sys.argv[2:]:
            if group in f:
                visit(group, f[group])
                if isinstance(f[group], h5py.Group):
                    f[group].visititems(visit)
except Exception as e:
    print(f"{type(e).__name__}: {str(e).splitlines()[0] if str(e) else ''}", file=sys.stderr)
    sys.exit(1)
"""


def check_readable(path, timeout):
    """MapError (one line) unless h5py reads the structure of every dataset of
    the groups open_map reads (its dimension scales, attributes and first
    element) within `timeout` seconds. Checked in a child process: on some damage
    (bytes of a dimension scale's list overwritten) HDF5 loops for ever, and
    a thread cannot be stopped."""
    import subprocess
    import sys

    env = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
    try:
        groups = [g for g, _ in GROUPS]
        p = subprocess.run([sys.executable, "-c", _CHECK_SCRIPT, path] + groups,
                           capture_output=True,
                           text=True, timeout=timeout, env=env, stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        raise MapError(f"{path}: reading its structure did not end within {timeout:g} s: a "
                       f"damaged map (HDF5 loops on it)") from None
    except OSError as e:
        raise MapError(f"{path}: cannot check it ({e})") from None
    if p.returncode < 0:
        raise MapError(f"{path} is a damaged map: h5py crashes on it (signal {-p.returncode})")
    if p.returncode != 0:
        why = (p.stderr.strip().splitlines() or [f"exit {p.returncode}"])[-1]
        raise MapError(f"{path} is a damaged map: h5py cannot read it ({why})")


def open_h5(path, h5py, warn=None, versions=(1, 2)):
    """PATH opened read-only with h5py; MapError (one line) unless it is a
    readable map of one of the layouts `versions`. `warn(message)` reports a
    map of an unknown schema name (default: a MapWarning). The one opener of
    the package and the tools (mdrmap.tools)."""
    check_file(path)
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        raise MapError(f"{path} is not a readable HDF5 file ({str(e).splitlines()[0]})") from None
    if "mdrmap_schema" not in f.attrs:
        f.close()
        raise MapError(f"{path} is not an mdrmap map (no root attribute mdrmap_schema)")
    name = schema_name(f)
    version = schema_version(f)
    if name not in SCHEMAS:
        message = (f"{path} has schema {name}; mdrmap reads {SCHEMA1} and {SCHEMA2} "
                   f"(reading it as {SCHEMA1 if version == 1 else SCHEMA2})")
        if warn is None:
            warnings.warn(message, MapWarning)
        else:
            warn(message)
    if version not in versions:
        f.close()
        raise MapError(f"{path} is an {SCHEMA1 if version == 1 else SCHEMA2} map; this tool "
                       f"reads {SCHEMA2 if version == 1 else SCHEMA1} maps: rerun the study with "
                       f"this version")
    if version == 1:
        need = ["results/status"] + [f"cases/{c}" for c in _CASE_COLS1]
    else:
        need = ["results/status", "cases/tau", "cases/v", "cases/w", "cases/T"]
    for item in need:
        if item not in f:
            f.close()
            raise MapError(f"{path} is an incomplete mdrmap map (no /{item})")
    if any(old in f and new not in f for new, old in OLD_OUTPUT_NAMES.items()):
        return Renamed(f, h5py)  # an old map's events/d_c as events/D_c
    return f


def require_groups(f, path, groups=("schema", "scales")):
    """MapError (one line naming the group) unless the open map has each of
    `groups`: /schema (units and meanings) and /scales (the reference scales
    of each case) are in every map this version writes."""
    for g in groups:
        if g not in f or not hasattr(f[g], "keys"):
            raise MapError(f"{path} has no /{g} group: it was made before mdrmap wrote /{g} "
                           f"(rerun the study with this version)")


def describe(f):
    """{"group/name": (unit, meaning)} from the map's /schema group, in the
    map's order; {} for a map written before /schema."""
    out = {}
    if "schema" not in f or not hasattr(f["schema"], "keys"):
        return out
    for group, g in f["schema"].items():
        if not hasattr(g, "keys"):
            continue
        for name, entry in g.items():
            out[f"{group}/{name}"] = (text(entry.attrs.get("unit", "")).rstrip("\0"),
                                      text(entry.attrs.get("meaning", "")).rstrip("\0"))
    return out


def case_columns(f, described=None):
    """The 1-D /cases columns (one value per case) of an open map, as its
    /schema lists them (the study's column order: the loading first); the
    per-segment /cases/w and /cases/T ([N, K]) are not among them."""
    described = describe(f) if described is None else described
    cols = [p.split("/", 1)[1] for p in described if p.startswith("cases/")]
    return [c for c in cols if f"cases/{c}" in f and len(f[f"cases/{c}"].shape) == 1]


def read_scales(f, path, described=None):
    """The map's /scales: {name: (values [N] as float, unit, meaning)} in the
    order of /schema/scales (length, depth, force, friction, time). MapError
    for a map without /scales (require_groups)."""
    import numpy as np

    require_groups(f, path, ("scales",))
    described = describe(f) if described is None else described
    names = [p.split("/", 1)[1] for p in described if p.startswith("scales/")]
    names += [k for k in f["scales"] if k not in names]
    out = {}
    for name in names:
        if name not in f["scales"]:
            raise MapError(f"{path}: /schema lists scales/{name}, the map has no /scales/{name}")
        unit, meaning = described.get(f"scales/{name}", ("", ""))
        out[name] = (np.asarray(f["scales"][name][()], dtype=float), unit, meaning)
    return out


def failure_messages(f, n):
    """Per case, why it failed ('' where no message)."""
    msgs = [""] * n
    if "failures/case" in f and "failures/message" in f:
        for i, m in zip(f["failures/case"][()], f["failures/message"][()]):
            if 0 <= int(i) < n:
                msgs[int(i)] = text(m).rstrip("\0").strip()
    elif "results/message" in f:
        msgs = [text(x).rstrip("\0").strip() for x in f["results/message"][()]]
    return msgs


def segment_axis(name):
    """A grid axis of the history: ("w" or "T", segment k from 1, scaled) for
    wk, wk_over_v, Tk, Tk_over_tau (and the seed's v1, v1_over_v as w1 and
    t_end_over_tau as T1_over_tau), else None."""
    if name == "t_end_over_tau":  # the seed's window: T1_over_tau
        return "T", 1, True
    m = re.fullmatch(r"(w|T|v)([1-9][0-9]*)(_over_(v|tau))?", name)
    if not m:
        return None
    kind = "w" if m.group(1) in ("w", "v") else "T"
    over = m.group(4)
    if (kind == "w" and over not in (None, "v")) or (kind == "T" and over not in (None, "tau")):
        return None
    return kind, int(m.group(2)), over is not None


# map group -> variable name prefix
GROUPS = [("cases", ""), ("results", ""), ("events", ""), ("analytic", "analytic_"),
          ("residuals", "residual_"), ("scales", "scale_"), ("timeseries", "ts_")]


def _attr(value):
    """An HDF5 attribute as a plain Python/numpy value (strings as str)."""
    import numpy as np

    if isinstance(value, (bytes, np.bytes_)) or getattr(value, "dtype", None) is not None and \
            value.dtype.kind == "S":
        return text(value).rstrip("\0")
    if isinstance(value, np.ndarray) and value.ndim == 0:
        return value.item()
    return value


def _read_h5(path):
    """Root attributes, /grid description and which groups the map has (h5py)."""
    import h5py
    import numpy as np

    with open_h5(path, h5py) as f:
        attrs = {k: _attr(f.attrs[k]) for k in f.attrs}
        n = int(f["results/status"].shape[0])
        groups = [g for g, _ in GROUPS if g in f and hasattr(f[g], "keys") and len(f[g])]
        grid = None
        if "grid" in f:
            g = f["grid"]
            try:
                axes = [a.strip() for a in text(g.attrs["axes"]).split(",") if a.strip()]
                values = [np.asarray(g[a][()], dtype=float) for a in axes]
                log = [int(k) for k in np.ravel(g.attrs["log"])] if "log" in g.attrs \
                    else [0] * len(axes)
                described = {a: (text(g[a].attrs.get("units", "")), text(g[a].attrs.get(
                    "long_name", ""))) for a in axes}
            except (KeyError, ValueError) as e:
                raise MapError(f"{path}: /grid is malformed ({e})") from None
            if math.prod(len(v) for v in values) != n:
                raise MapError(f"{path}: /grid axes {axes} of shape "
                                f"{[len(v) for v in values]} do not fit {n} cases")
            renamed = [case_name(a) for a in axes]  # an old map's FN: F0
            described = {case_name(a): d for a, d in described.items()}
            grid = {"axes": renamed, "values": values, "log": log, "described": described}
        scaled = "case" in f and f["case"].attrs.get("CLASS") == b"DIMENSION_SCALE"
        version = schema_version(f)
        messages = failure_messages(f, n) if version == 2 else None
    return attrs, n, groups, grid, scaled, version, messages


def _open_group(path, group, prefix, n, scaled, version):
    """One group of the map as a Dataset along `case`, its variables renamed
    with `prefix` and marked with map_path (the /cases columns as coordinates)."""
    import xarray as xr

    try:
        # mdrmap-map/2: the fill value of undefined values becomes NaN
        ds = xr.open_dataset(path, engine="h5netcdf", group=group, decode_times=False,
                             decode_timedelta=False, mask_and_scale=version == 2,
                             phony_dims=None if scaled else "sort")
    except (OSError, ValueError) as e:
        raise MapError(f"{path}: cannot open /{group} with xarray "
                       f"({str(e).splitlines()[0]})") from None
    if not scaled:  # a map without dimension scales: name the phony dimensions
        second = "sample" if group == "timeseries" else "event"
        names = {}
        for var in ds.data_vars.values():
            want = ["case", second] if len(var.dims) == 2 or var.shape[0] == n else [second]
            for dim, name in zip(var.dims, want):
                if names.setdefault(dim, name) != name:
                    raise MapError(f"{path}: /{group} has no dimension scales and its "
                                   f"dimensions are ambiguous")
        ds = ds.rename_dims(names)
    if ds.sizes.get("case") != n:
        raise MapError(f"{path}: /{group} is not along the {n} cases")
    for name in ds.data_vars:
        ds[name].attrs["map_path"] = f"{group}/{name}"
    old = {o.split("/", 1)[1]: n.split("/", 1)[1] for n, o in OLD_OUTPUT_NAMES.items()
           if n.startswith(group + "/")}  # an old map's events/d_c: D_c
    ds = ds.rename({k: old[k] for k in list(ds.data_vars)
                    if k in old and old[k] not in ds.data_vars}) if old else ds
    ds = ds.rename({k: prefix + k for k in ds.data_vars}) if prefix else ds
    if group == "cases":
        ds = ds.rename({k: case_name(k) for k in ds.data_vars
                        if case_name(k) != k and case_name(k) not in ds.data_vars})
        ds = ds.set_coords(list(ds.data_vars))
    ds.attrs = {}
    return ds


def _grid_attrs(grid):
    """The Dataset attributes that describe a grid study's axes."""
    out = {"grid_axes": ",".join(grid["axes"]), "grid_shape": [len(v) for v in grid["values"]],
           "grid_log": grid["log"]}
    for a, v in zip(grid["axes"], grid["values"]):
        out[f"grid_{a}"] = v
        unit, meaning = grid["described"][a]
        if unit:
            out[f"grid_{a}_units"] = unit
        if meaning:
            out[f"grid_{a}_long_name"] = meaning
    return out


def open_map(path, timeout=60):
    """The map at `path` as one xarray Dataset (see the module's help). Raises
    MapError (one line) when `path` is not a readable mdrmap map: not a
    regular HDF5 file, or damaged (h5py cannot read the structure of every
    dataset within `timeout` seconds, checked in a child process)."""
    import xarray as xr

    import numpy as np

    if isinstance(path, os.PathLike):
        path = os.fspath(path)
    if not isinstance(path, str):
        raise MapError(f"open_map needs the path of a map (str or os.PathLike), got "
                       f"{type(path).__name__}")
    check_file(path)
    check_readable(path, timeout)
    attrs, n, groups, grid, scaled, version, messages = _read_h5(path)
    parts = [_open_group(path, group, prefix, n, scaled, version)
             for group, prefix in GROUPS if group in groups]
    out = xr.merge(parts, compat="identical", join="exact", combine_attrs="override")
    if messages is not None:
        out["message"] = xr.Variable(("case",), np.array(messages, dtype=object),
                                     {"long_name": "why a case failed (empty otherwise)",
                                      "map_path": "failures/message"})
    out.attrs = dict(attrs)
    if grid:
        out.attrs.update(_grid_attrs(grid))
    return out


# a relaxation spectrum's term k: its modulus Gk or its time tauk (k = 1..32)
_SPECTRUM_KEY = re.compile(r"(G|tau)([1-9][0-9]*)")
MATERIAL = "material"  # to_grid's dimension of a spectrum's varied terms


def is_spectrum_key(name):
    """Whether a grid axis is a spectrum's term (G1, tau1, ..., G32, tau32)."""
    return _SPECTRUM_KEY.fullmatch(name) is not None


def _grid_dims(axes, values):
    """to_grid's dimensions: [(name, [axis indices])] over the axes with more
    than one value, in the grid's order; the spectrum's such axes (Gk, tauk)
    together as one dimension `material` (where the first of them is)."""
    dims, material = [], None
    for i, (a, v) in enumerate(zip(axes, values)):
        if len(v) < 2:
            continue
        if is_spectrum_key(a):
            if material is None:
                material = []
                dims.append((MATERIAL, material))
            material.append(i)
        else:
            dims.append((a, [i]))
    return dims


def to_grid(ds):
    """The Dataset of a grid study (open_map) with the grid's axes as dimensions
    (see the module's help). Raises MapError for a map without /grid."""
    import numpy as np
    import xarray as xr

    if not isinstance(ds, xr.Dataset):
        raise MapError(f"to_grid needs the Dataset of open_map(path), got {type(ds).__name__}")
    if "grid_axes" not in ds.attrs:
        raise MapError("not a grid study (the map has no /grid): to_grid needs the grid's axes")
    if "case" not in ds.dims:
        raise MapError("to_grid needs the Dataset of open_map(path), along `case`")
    axes = [a for a in str(ds.attrs["grid_axes"]).split(",") if a]
    try:
        values = [np.atleast_1d(np.asarray(ds.attrs[f"grid_{a}"], dtype=float)) for a in axes]
    except (KeyError, TypeError, ValueError) as e:
        raise MapError(f"the Dataset's grid attributes are incomplete ({e})") from None
    shape = tuple(len(v) for v in values)
    n = ds.sizes["case"]
    if math.prod(shape) != n:
        raise MapError(f"grid axes {axes} of shape {list(shape)} do not fit {n} cases")
    dims = _grid_dims(axes, values)
    clash = [d for d, _ in dims if d in ds.dims]
    if clash:
        raise MapError(f"grid axis {clash[0]!r} is also a dimension of the Dataset")
    # numpy's arrays have at most 32 dimensions (64 from numpy 2)
    max_dims = 64 if int(np.__version__.split(".")[0]) >= 2 else 32
    if len(dims) + 1 > max_dims:
        raise MapError(f"the grid has {len(dims)} axes of more than one value; numpy arrays have "
                       f"at most {max_dims} dimensions: use open_map's rows along `case` "
                       f"(grid_* attributes name each case's axis values)")

    _check_case_order(ds, axes, values, shape)
    return _reshaped(ds, axes, values, dims, n)


def _segment_column(ds, name, cache):
    """A history axis's values per case from /cases/w or /cases/T [N, K]
    (mdrmap-map/2), or None where `name` is not such an axis."""
    import numpy as np

    seg = segment_axis(name) if name not in ds.variables else None
    if seg is None or seg[0] not in ds.variables or ds[seg[0]].ndim != 2:
        return None
    kind, k, over = seg
    if kind not in cache:
        cache[kind] = np.asarray(ds[kind].values, dtype=float)
    col = cache[kind]
    if k > col.shape[1]:
        raise MapError(f"grid axis {name!r} names segment {k}, the map has {col.shape[1]}")
    have = col[:, k - 1]
    if over:
        # TK_over_tau multiplies the case's time scale (/scales/time; tau in a
        # map made before /scales)
        ref_name = "v" if kind == "w" else "scale_time" if "scale_time" in ds.variables else "tau"
        if ref_name not in cache:
            cache[ref_name] = np.asarray(ds[ref_name].values, dtype=float)
        ref = cache[ref_name]
        with np.errstate(divide="ignore", invalid="ignore"):
            have = np.where(ref != 0, have / ref, np.nan)
    return have


def _check_case_order(ds, axes, values, shape):
    """MapError unless the /cases columns are the grid's axes in C order."""
    import numpy as np

    # the grid's values per case (C order, last axis fastest); an axis of one
    # value is that value everywhere
    n = math.prod(shape)
    varied = [i for i, v in enumerate(values) if len(v) > 1]
    mesh = np.meshgrid(*[values[i] for i in varied], indexing="ij") if varied else []
    want = {a: np.full(n, v[0]) for a, v in zip(axes, values) if len(v) == 1}
    want.update({axes[i]: m.ravel() for i, m in zip(varied, mesh)})
    if "v1_over_v" in want and "v" in want:
        want.setdefault("v1", want["v1_over_v"] * want["v"])
    cache = {}
    for a, w in want.items():
        seg = _segment_column(ds, a, cache)
        if seg is not None:
            ok = np.isfinite(seg)  # Tk_over_tau where nothing relaxes: no time scale
            same = np.allclose(seg[ok], w[ok], rtol=1e-12, atol=0)
        elif a not in ds.variables:
            continue
        else:
            have = np.asarray(ds[a].values, dtype=float).ravel()
            same = np.array_equal(have, w) if a in axes else \
                np.allclose(have, w, rtol=1e-12, atol=0)
        if not same:
            raise MapError(f"/cases/{a} does not follow the grid's axes {axes} in C order: "
                           f"not a grid study's case order")


def _regrid(arr, kept_shape, dims, kept):
    """`arr` [N, ...] to the dimensions `dims` (the C order of the kept axes,
    each dimension's axes made adjacent and merged)."""
    rest = arr.shape[1:]
    order = [kept.index(i) for _, idx in dims for i in idx]
    order += [len(kept) + j for j in range(len(rest))]  # the variable's own dimensions last
    out = arr.reshape(kept_shape + rest).transpose(order)
    sizes = tuple(math.prod(kept_shape[kept.index(i)] for i in idx) for _, idx in dims)
    return out.reshape(sizes + rest)


def _axis_attrs(ds, a):
    """The units and long_name of grid axis `a` (from the Dataset's attributes)."""
    return {key: ds.attrs[f"grid_{a}_{key}"] for key in ("units", "long_name")
            if f"grid_{a}_{key}" in ds.attrs}


def _reshaped(ds, axes, values, dims, n):
    """Every variable along `case` reshaped to the grid's dimensions (see to_grid)."""
    import numpy as np
    import xarray as xr

    kept = [i for _, idx in dims for i in idx]
    kept.sort()
    kept_shape = tuple(len(values[i]) for i in kept)
    names = tuple(d for d, _ in dims)
    coords = {}
    for d, idx in dims:
        if d != MATERIAL:
            coords[d] = xr.Variable((d,), values[idx[0]], _axis_attrs(ds, d))
            continue
        mesh = np.meshgrid(*[values[i] for i in idx], indexing="ij")
        for i, m in zip(idx, mesh):
            coords[axes[i]] = xr.Variable((MATERIAL,), m.ravel(), _axis_attrs(ds, axes[i]))
    for a, v in zip(axes, values):
        if len(v) == 1:  # an axis of one value: a scalar coordinate
            coords[a] = xr.Variable((), v[0], _axis_attrs(ds, a))
    coords["case"] = xr.Variable(names, _regrid(np.arange(n), kept_shape, dims, kept),
                                 {"long_name": "row of the case in the map"})
    data = {}
    for name, var in ds.variables.items():
        if name in axes:
            continue  # now a coordinate of the grid
        if "case" not in var.dims:  # e.g. ts_segment: kept as it is
            (coords if name in ds.coords else data)[name] = var
            continue
        if var.dims[0] != "case" or "case" in var.dims[1:]:
            raise MapError(f"variable {name!r} is not along `case` first: cannot reshape it")
        new = xr.Variable(names + var.dims[1:],
                          _regrid(np.asarray(var.values), kept_shape, dims, kept), var.attrs)
        (coords if name in ds.coords else data)[name] = new
    attrs = {k: v for k, v in ds.attrs.items()}
    return xr.Dataset(data, coords=coords, attrs=attrs)
