"""Shared by the map tools (plot_map, plot_timeseries, map_summary, map_healing,
map_steps, map_rate_state, map_friction_velocity, mapxr): opening an mdrmap
map with clear one-line errors, and reading it.

Two layouts exist (the root attribute mdrmap_schema says which):

  mdrmap-map/1  one velocity step per case: /cases/{d,R,tau,v,v1,G},
                /results/<q>_{pre,jump,post} and message, time series [N, S];
  mdrmap-map/2  a history of K segments per case (docs/map-schema.md):
                /cases/{d or FN,R,tau,G,v} [N] and /cases/{w,T} [N, K],
                /events/<m> [N, K], /analytic/<q>_ss [N, K], /failures,
                time series [N, K*S] with /timeseries/segment [K*S];
                undefined values hold the netCDF fill value FILL (read_masked
                turns them into NaN).

Not a script: the tools import it from their own directory.
"""
import argparse
import importlib.util
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def _load_maps():
    """src/python/mdrmap/maps.py, the Python package's map reader, as a module
    (loaded from the source tree: the tools need no build)."""
    path = os.path.join(HERE, os.pardir, "src", "python", "mdrmap", "maps.py")
    spec = importlib.util.spec_from_file_location("mdrmap_maps", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


maps = _load_maps()
# the schema names and the readers of text and schema, from the package
SCHEMA1, SCHEMA2, SCHEMAS = maps.SCHEMA1, maps.SCHEMA2, maps.SCHEMAS
SCHEMA = SCHEMA2  # what mdrmap writes now
text, schema_name, schema_version = maps.text, maps.schema_name, maps.schema_version
# The /cases columns of schema-1 maps written before /schema (the fallback of case_columns)
CASE_COLS = ["d", "R", "tau", "v", "v1", "G"]
# The 1-D /cases columns of a schema-2 map, in their order (loading first: d or FN)
CASE_COLS2 = ["d", "FN", "R", "tau", "G", "v"]
# netCDF's default fill value for doubles: an undefined value in a schema-2 map
FILL = 9.969209968386869e36
# Hertz: FN = 16/3 G a0^3 / R; the maximum of the stationary friction under load
# (docs/design.md, "Load control")
ZETA0_STAR = 3 ** 0.5 * ((3 + 3 ** 0.5) / 9) ** (1 / 3)
MU_STAR = 1.5 * (3 ** 0.5 - 1) * ((3 + 3 ** 0.5) / 9) ** (1 / 3)


class UserError(Exception):
    """A problem with the input: reported in one line, exit code 2."""


class Parser(argparse.ArgumentParser):
    def error(self, message):  # one line instead of usage + message
        raise UserError(f"{message} (see --help)")


def v1_refused(path):
    """The one line a tool gives for a schema-1 map it does not read."""
    return (f"{path} is an {SCHEMA1} map; this tool reads {SCHEMA2} maps: rerun the study "
            f"with this version")


def open_map(path, h5py, prog, versions=(1, 2)):
    """Opens PATH read-only; UserError unless it is a readable mdrmap map of one of
    the schema `versions` (1, 2)."""
    if not os.path.exists(path):
        raise UserError(f"no such file: {path}")
    if os.path.isdir(path):
        raise UserError(f"{path} is a directory, not an mdrmap map")
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        raise UserError(f"{path} is not a readable HDF5 file ({str(e).splitlines()[0]})") from None
    if "mdrmap_schema" not in f.attrs:
        f.close()
        raise UserError(f"{path} is not an mdrmap map (no root attribute mdrmap_schema)")
    name = schema_name(f)
    version = schema_version(f)
    if name not in SCHEMAS:
        print(f"{prog}: warning: {path} has schema {name}; this tool reads {SCHEMA1} and "
              f"{SCHEMA2} (reading it as {SCHEMA1 if version == 1 else SCHEMA2})", file=sys.stderr)
    if version not in versions:
        f.close()
        if version == 1:
            raise UserError(v1_refused(path))
        raise UserError(f"{path} is an {SCHEMA2} map; this tool reads {SCHEMA1} maps only")
    if version == 1:
        need = ["results/status"] + [f"cases/{c}" for c in CASE_COLS[:5]]
    else:
        need = ["results/status", "cases/R", "cases/tau", "cases/v", "cases/w", "cases/T"]
        if "cases/d" not in f and "cases/FN" not in f:
            need.append("cases/d")  # reported as missing below
    for item in need:
        if item not in f:
            f.close()
            raise UserError(f"{path} is an incomplete mdrmap map (no /{item})")
    return f


def read_masked(ds):
    """A dataset as a float array with the fill value FILL (and the value of the
    dataset's attribute _FillValue, if it has one) as NaN. Integer and string
    datasets come back as they are."""
    import numpy as np

    arr = ds[()]
    if not hasattr(arr, "dtype") or arr.dtype.kind != "f":
        return arr
    arr = np.array(arr, dtype=float)
    fill = ds.attrs.get("_FillValue", None) if hasattr(ds, "attrs") else None
    mask = arr == FILL
    if fill is not None:
        fv = np.ravel(np.asarray(fill, dtype=float))
        if fv.size:
            mask |= arr == fv[0]
    arr[mask] = np.nan
    return arr


def schema(f):
    """{"group/name": (unit, meaning)} from the map's /schema group, in the map's
    order; {} for a map written before /schema."""
    out = {}
    if "schema" not in f or not hasattr(f["schema"], "keys"):
        return out
    for group, g in f["schema"].items():
        if not hasattr(g, "keys"):
            continue
        for name, entry in g.items():
            out[f"{group}/{name}"] = (text(entry.attrs.get("unit", "")),
                                      text(entry.attrs.get("meaning", "")))
    return out


def case_columns(f, described=None):
    """The 1-D /cases columns of an open map (one value per case): those its
    /schema lists (the map's order: the study's column order), else, for a map
    without /schema, CASE_COLS2 (d or FN, R, tau, G, v; schema 2) or CASE_COLS. The per-segment columns /cases/w and /cases/T of a
    schema-2 map ([N, K]) are not among them. `described`: schema(f), when
    already read."""
    described = schema(f) if described is None else described
    cols = [p.split("/", 1)[1] for p in described if p.startswith("cases/")]
    cols = [c for c in cols if f"cases/{c}" in f and len(f[f"cases/{c}"].shape) == 1]
    if cols:
        return cols
    if schema_version(f) == 2:  # a map without /schema: the documented order
        return [c for c in CASE_COLS2 if f"cases/{c}" in f and len(f[f"cases/{c}"].shape) == 1]
    return list(CASE_COLS)


def failure_messages(f, n):
    """Per case, why it failed ('' where no message): /failures/{case,message} of a
    schema-2 map, /results/message of a schema-1 map."""
    msgs = [""] * n
    if "failures/case" in f and "failures/message" in f:
        for i, m in zip(f["failures/case"][()], f["failures/message"][()]):
            if 0 <= int(i) < n:
                msgs[int(i)] = text(m).rstrip("\0").strip()
    elif "results/message" in f:
        msgs = [text(x).rstrip("\0").strip() for x in f["results/message"][()]]
    return msgs


def read_grid(f, n, path):
    """/grid of an open map as {"axes", "shape", "log", "values"}, or None for a
    [cases] map; UserError when it is malformed or does not fit the n cases."""
    import numpy as np

    if "grid" not in f:
        return None
    g = f["grid"]
    try:
        axes = [a.strip() for a in text(g.attrs["axes"]).split(",") if a.strip()]
        values = [np.asarray(g[a][()], dtype=float) for a in axes]
        shape = [int(k) for k in np.ravel(g.attrs["shape"])] if "shape" in g.attrs \
            else [len(v) for v in values]
        log = [bool(k) for k in np.ravel(g.attrs["log"])] if "log" in g.attrs \
            else [False] * len(axes)
    except (KeyError, ValueError) as e:
        raise UserError(f"{path}: /grid is malformed ({e})") from None
    if len(shape) != len(axes) or len(log) != len(axes) or math.prod(shape) != n or \
            any(len(v) != k for v, k in zip(values, shape)):
        raise UserError(f"{path}: /grid axes {axes} of shape {shape} do not fit {n} cases")
    return {"axes": axes, "shape": shape, "log": log, "values": values}


def segment_axis(name):
    """A grid axis of the history: ("w" or "T", segment k from 1, scaled) for
    wk, wk_over_v, Tk, Tk_over_tau (and the seed's v1, v1_over_v as w1 and
    t_end_over_tau as T1_over_tau), else None."""
    import re

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


def axis_values_per_case(m, axis, np):
    """The value of grid axis `axis` for every case of a loaded schema-2 map `m`
    (load_cases), computed from /cases (the loading, R, tau, G, v, wk, Tk and the
    scaled wk_over_v, Tk_over_tau)."""
    if axis in m["cols"]:
        return m["cols"][axis]
    seg = segment_axis(axis)
    if seg is None:
        return None
    kind, k, scaled = seg
    if k > m["K"]:
        return None
    x = m[kind][:, k - 1]
    if not scaled:
        return x
    ref = m["cols"]["v"] if kind == "w" else m["cols"]["tau"]
    with np.errstate(divide="ignore", invalid="ignore"):
        return x / ref


def load_cases(f, path, np):
    """The case description of an open schema-2 map: {"n", "K", "status", "cols"
    (1-D /cases columns), "w", "T" ([N, K]), "loading" ("force" or "depth"),
    "a" (the length scale: a0 = (3 FN R / 16 G)^(1/3) under load, a1 = sqrt(R d)
    at depth), "a_name" ("a0" or "a1"), "mu_scale" (a / R), "zeta" (v tau / a),
    "grid" (read_grid or None), "message"}."""
    n = int(f["results/status"].shape[0])
    m = {"path": path, "n": n, "status": f["results/status"][()].astype(int)}
    m["cols"] = {c: f[f"cases/{c}"][()].astype(float) for c in case_columns(f)}
    if "G" not in m["cols"]:
        m["cols"]["G"] = np.ones(n)
    m["w"] = np.asarray(f["cases/w"][()], dtype=float).reshape(n, -1)
    m["T"] = np.asarray(f["cases/T"][()], dtype=float).reshape(n, -1)
    m["K"] = int(m["w"].shape[1])
    load = "FN" in m["cols"]
    m["loading"] = "force" if load else "depth"
    c = m["cols"]
    with np.errstate(divide="ignore", invalid="ignore"):
        if load:
            m["a"] = np.cbrt(3 * c["FN"] * c["R"] / (16 * c["G"]))
        else:
            m["a"] = np.sqrt(c["R"] * c["d"])
        m["mu_scale"] = m["a"] / c["R"]
        m["zeta"] = c["v"] * c["tau"] / m["a"]
    m["a_name"] = "a0" if load else "a1"
    m["zeta_name"] = "zeta0" if load else "zeta"
    m["grid"] = read_grid(f, n, path)
    m["message"] = failure_messages(f, n)
    return m


def resolve_axis(name, axes):
    """The grid axis `name` means: itself, or its history alias (v1_over_v is
    w1_over_v, v1 is w1, and back); None when there is none."""
    if name in axes:
        return name
    seg = segment_axis(name)
    if seg is None:
        return None
    for a in axes:
        if segment_axis(a) == seg:
            return a
    return None


def grid_index(m, np):
    """{axis: the index of every case along it} for a grid map (C order over the
    axes, last fastest)."""
    g = m["grid"]
    idx = np.unravel_index(np.arange(m["n"]), tuple(g["shape"]))
    return dict(zip(g["axes"], idx))


def select_cases(m, sel, np, option="--select"):
    """Cases (bool [N]) at the values nearest to sel = {axis: value}: grid axes of a
    grid map (by their grid index), else /cases columns and wk, Tk, wk_over_v,
    Tk_over_tau. Returns (keep, notes) with a note per axis saying the value used."""
    keep = np.ones(m["n"], dtype=bool)
    notes = []
    g = m["grid"]
    for name, target in sel.items():
        if g is not None:
            a = resolve_axis(name, g["axes"])
            if a is None:
                raise UserError(f"{option} {name}={fmt(target)}: no grid axis {name!r} "
                                f"(axes: {', '.join(g['axes'])})")
            vals = g["values"][g["axes"].index(a)]
            j = nearest_index(vals, target, np)
            keep &= grid_index(m, np)[a] == j
            msg = f"{option} {name}={fmt(target)} -> {a}={fmt(vals[j])} (value {j + 1} of {len(vals)})"
        else:
            x = axis_values_per_case(m, name, np)
            if x is None:
                names = list(m["cols"]) + [f"{k}{s}" for s in range(1, m["K"] + 1) for k in "wT"]
                raise UserError(f"{option} {name}={fmt(target)}: no case parameter {name!r} "
                                f"(a [cases] map: {', '.join(names)}, wk_over_v, Tk_over_tau)")
            u = np.unique(x[np.isfinite(x)])
            j = nearest_index(u, target, np)
            keep &= np.isclose(x, u[j], rtol=1e-9, atol=0)
            msg = f"{option} {name}={fmt(target)} -> {name}={fmt(u[j])}"
        notes.append(f"{msg}: {int(keep.sum())} case(s) left")
    return keep, notes


def parse_assignments(specs, option):
    """["k=v", "k=v,k2=v2", ...] -> {k: float}; UserError (one line) for bad ones."""
    out = {}
    for spec in specs or []:
        for part in spec.split(","):
            part = part.strip()
            if not part:
                continue
            if "=" not in part:
                raise UserError(f"{option} {spec!r}: expected AXIS=VALUE, e.g. {option} v=0.1")
            k, v = (s.strip() for s in part.split("=", 1))
            try:
                x = float(v)
            except ValueError:
                raise UserError(f"{option} {part}: {v!r} is not a number") from None
            if not math.isfinite(x):
                raise UserError(f"{option} {part}: {v!r} is not a finite number")
            out[k] = x
    return out


def nearest_index(values, target, np):
    """Index of the value nearest to target (in log distance when all are > 0)."""
    values = np.asarray(values, dtype=float)
    if target > 0 and np.all(values > 0):
        return int(np.argmin(np.abs(np.log(values / target))))
    return int(np.argmin(np.abs(values - target)))


def fmt(x, digits=3):
    """Compact number: 1e-04 -> 1e-4, 0.5 -> 0.5, nan -> nan."""
    x = float(x)
    if x == 0:
        return "0"
    if not math.isfinite(x):
        return str(x)
    s = f"{x:.{digits}g}" if 1e-3 <= abs(x) < 1e5 else f"{x:.{digits - 1}e}"
    if "e" in s:
        mant, exp = s.split("e")
        if "." in mant:
            mant = mant.rstrip("0").rstrip(".")
        return f"{mant}e{int(exp)}"
    return s


def writable(output):
    """UserError unless output's directory exists."""
    outdir = os.path.dirname(os.path.abspath(output))
    if not os.path.isdir(outdir):
        raise UserError(f"cannot write {output}: no such directory {outdir}")


SELECT_HELP = ("keep the cases at the grid value of AXIS nearest to VALUE "
               "(repeatable, or comma-separated)")


def map_tool_parser(prog, doc, map_help, suffix):
    """The parser of a map_* plotting tool with its first arguments: the map
    (help `map_help`) and -o/--output (default <map name><suffix>, which
    parse_map_tool_args fills in). Add the tool's own options, add_select_option
    and add_figure_options after them, in the order --help lists them."""
    ap = Parser(prog=prog, description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("map", help=map_help)
    ap.add_argument("-o", "--output", default=None,
                    help=f"PNG to write (default: <map name>{suffix})")
    ap.output_suffix = suffix
    return ap


def add_select_option(ap, help=SELECT_HELP):
    """--select AXIS=VALUE (repeatable), read by parse_map_tool_args."""
    ap.add_argument("--select", action="append", metavar="AXIS=VALUE", help=help)


def add_figure_options(ap):
    """--title and --dpi (checked by parse_map_tool_args)."""
    ap.add_argument("--title", default=None, help="figure title")
    ap.add_argument("--dpi", type=int, default=120, help="resolution (default 120)")


def parse_map_tool_args(ap, argv):
    """Parses argv with a map_tool_parser and checks the common options: (args,
    sel = the --select assignments {axis: value}, output = the PNG to write, in a
    directory that exists). UserError (one line) for a bad --dpi, --select or
    output directory."""
    args = ap.parse_args(argv)
    if args.dpi <= 0 or args.dpi > 1200:
        raise UserError(f"--dpi {args.dpi}: must be in 1..1200")
    sel = parse_assignments(args.select, "--select")
    output = args.output or (os.path.splitext(os.path.basename(args.map))[0] + ap.output_suffix)
    writable(output)
    return args, sel, output


def open_map2(path, np, prog):
    """Opens the mdrmap-map/2 map at path for a tool that reads only schema 2:
    (f, load_cases(f)), f open (use it in a with block); UserError as open_map."""
    import h5py

    f = open_map(path, h5py, prog, versions=(2,))
    try:
        return f, load_cases(f, path, np)
    except BaseException:
        f.close()
        raise


def save_figure(fig, output, dpi):
    """Writes a matplotlib figure; UserError (one line) if the file cannot be written."""
    try:
        fig.savefig(output, dpi=dpi)
    except OSError as e:
        raise UserError(f"cannot write {output}: {e.strerror or e}") from None


def run_tool(main, prog):
    """Runs main(); a UserError becomes one line on stderr and exit code 2."""
    try:
        return main()
    except UserError as e:
        print(f"{prog}: {e}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # e.g. piped into head
        try:
            sys.stdout = None
        finally:
            return 0
    except KeyboardInterrupt:
        return 130
