"""Shared by the map tools (plot_map, plot_timeseries, map_summary, map_healing,
map_steps, map_rate_state, map_friction_velocity, mapxr): opening an mdrmap
map with clear one-line errors, and reading it.

The tools read mdrmap-map/2 maps (a history of K segments per case,
docs/reference/map-schema.md): /cases/<p> [N] and /cases/{w,T} [N, K], /events/<m>
[N, K], /analytic/<q>_ss [N, K], /failures, time series [N, K*S] with
/timeseries/segment [K*S]; undefined values hold the netCDF fill value FILL
(read_masked turns them into NaN). Everything a tool names comes from the
map: the case columns and each dataset's unit and meaning from /schema, the
reference scales (length, depth, force, friction, time) from /scales. A map
without /schema or /scales (older ones) is refused in one line naming the
group; an mdrmap-map/1 map likewise.

The opener and the readers of /schema and /scales are the package's
(mdrmap.maps): one map loader for the package and the tools.

Not a tool: the tools of the package (mdrmap.tools) import it.
"""
import argparse
import math
import os
import sys

from .. import maps
# the schema names and the readers of text and schema, from the package
SCHEMA1, SCHEMA2, SCHEMAS = maps.SCHEMA1, maps.SCHEMA2, maps.SCHEMAS
SCHEMA = SCHEMA2  # what mdrmap writes now
text, schema_name, schema_version = maps.text, maps.schema_name, maps.schema_version
failure_messages, segment_axis = maps.failure_messages, maps.segment_axis
# netCDF's default fill value for doubles: an undefined value in a schema-2 map
FILL = 9.969209968386869e36
# The maximum of the stationary friction under load, in the map's scales
# (zeta0* = v tau / a0, mu* / (a0/R)): constants of the closed form,
# docs/design.md "Load control" (sqrt(3) ((3 + sqrt(3))/9)^(1/3) and
# 3/2 (sqrt(3) - 1) ((3 + sqrt(3))/9)^(1/3))
ZETA0_STAR = 1.397964867446765
MU_STAR = 0.8862742123631036


class UserError(Exception):
    """A problem with the input: reported in one line, exit code 2."""


class Parser(argparse.ArgumentParser):
    """The tools' argument parser: usage as `python -m mdrmap TOOL`, errors in one line."""

    def __init__(self, *args, prog=None, **kwargs):
        if prog is not None and " " not in prog:
            prog = "python -m mdrmap " + prog
        super().__init__(*args, prog=prog, **kwargs)

    def error(self, message):  # one line instead of usage + message
        raise UserError(f"{message} (see --help)")


def open_map(path, h5py, prog):
    """Opens PATH read-only (the package's maps.open_h5); UserError (one line)
    unless it is a readable mdrmap-map/2 map with /schema and /scales."""
    warn = lambda message: print(f"{prog}: warning: {message}", file=sys.stderr)  # noqa: E731
    try:
        f = maps.open_h5(path, h5py, warn, versions=(2,))
    except maps.MapError as e:
        raise UserError(str(e)) from None
    try:
        maps.require_groups(f, path)
    except maps.MapError as e:
        f.close()
        raise UserError(str(e)) from None
    except BaseException:
        f.close()
        raise
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
    """{"group/name": (unit, meaning)} from the map's /schema, in the map's order."""
    return maps.describe(f)


def case_columns(f, described=None):
    """The 1-D /cases columns of an open map, in the order its /schema lists them."""
    return maps.case_columns(f, described)


def read_grid(f, n, path):
    """/grid of an open map as {"axes" (F0 for an old map's FN), "shape", "log",
    "values"}, or None for a [cases] map; UserError when it is malformed or does not fit the n cases."""
    import numpy as np

    if "grid" not in f:
        return None
    g = f["grid"]
    try:
        axes = [a.strip() for a in text(g.attrs["axes"]).split(",") if a.strip()]
        values = [np.asarray(g[a][()], dtype=float) for a in axes]
        axes = [maps.case_name(a) for a in axes]  # an old map's FN: F0
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
    # TK_over_tau multiplies the case's time scale (/scales/time: tau for the
    # Kelvin foundation, the longest shifted relaxation time of a spectrum)
    ref = m["cols"]["v"] if kind == "w" else m["scales"]["time"]
    with np.errstate(divide="ignore", invalid="ignore"):
        return x / ref


def load_cases(f, path, np):
    """The case description of an open map (open_map): {"n", "K", "status",
    "cols" (the 1-D /cases columns /schema lists, F0 for an old map's FN), "w", "T" ([N, K]), "loading"
    (the root attribute: "force" or "depth"), "schema" (schema(f)), "scales"
    ({name: values [N]} of /scales: length, depth, force, friction, time),
    "a" (/scales/length: a0 under load, a1 at depth), "a_name" ("a0" or "a1"),
    "mu_scale" (/scales/friction), "zeta" (v over the velocity scale
    length / time), "zeta_name", "grid" (read_grid or None), "message"}.
    Nothing here computes a scale: they are the map's."""
    n = int(f["results/status"].shape[0])
    m = {"path": path, "n": n, "status": f["results/status"][()].astype(int)}
    m["schema"] = schema(f)
    # under today's names: an old map's prescribed load /cases/FN as F0
    m["cols"] = {maps.case_name(c): f[f"cases/{c}"][()].astype(float)
                 for c in case_columns(f, m["schema"])}
    m["w"] = np.asarray(f["cases/w"][()], dtype=float).reshape(n, -1)
    m["T"] = np.asarray(f["cases/T"][()], dtype=float).reshape(n, -1)
    m["K"] = int(m["w"].shape[1])
    try:
        scales = maps.read_scales(f, path, m["schema"])
    except maps.MapError as e:
        raise UserError(str(e)) from None
    m["scales"] = {k: v[0] for k, v in scales.items()}
    m["scale_units"] = {k: v[1] for k, v in scales.items()}
    for name in ("length", "friction", "time"):
        if name not in m["scales"]:
            raise UserError(f"{path}: /scales has no {name}")
    loading = text(f.attrs.get("loading", "")).rstrip("\0")
    m["loading"] = loading if loading in ("force", "depth") else "depth"
    load = m["loading"] == "force"
    m["a"] = m["scales"]["length"]
    m["mu_scale"] = m["scales"]["friction"]
    with np.errstate(divide="ignore", invalid="ignore"):
        m["zeta"] = m["cols"]["v"] * m["scales"]["time"] / m["a"]
    m["a_name"] = "a0" if load else "a1"
    m["zeta_name"] = "zeta0" if load else "zeta"
    m["grid"] = read_grid(f, n, path)
    m["message"] = failure_messages(f, n)
    return m


# how a dataset is scaled, by its /schema unit: (scale, its symbol given a_name)
SCALE_OF_UNIT = {"length": "length", "force": "force", "time": "time"}


def scale_of(m, key):
    """The name of the /scales entry a dataset "group/name" (or a per-event
    column "group/name_<k>") is measured in, from its /schema unit and
    meaning: lengths by the length scale (depths by the depth scale), forces by
    the force scale, times by the time scale, dimensionless friction
    quantities (mu, a, b, a - b) by the friction scale; None for residuals,
    error estimates and anything else."""
    group, name = key.split("/", 1)
    entry = m["schema"].get(key)
    if entry is None and "_" in name and name.rsplit("_", 1)[1].isdigit():
        entry = m["schema"].get(f"{group}/{name.rsplit('_', 1)[0]}")
    if entry is None or group in ("residuals", "cases", "grid", "scales"):
        return None
    unit, meaning = entry
    if unit == "length" and meaning.startswith("indentation depth"):
        return "depth" if "depth" in m["scales"] else None
    if unit in SCALE_OF_UNIT:
        return SCALE_OF_UNIT[unit] if SCALE_OF_UNIT[unit] in m["scales"] else None
    if unit == "number" and "error" not in meaning:
        return "friction"
    return None


def scale_symbol(m, scale):
    """A short name of a scale in a label: a0 or a1, a0/R, ..., tau."""
    a = m["a_name"]
    return {"length": a, "depth": "d0" if a == "a0" else "d", "force": "F0" if a == "a0"
            else "F(a1)", "friction": f"{a}/R", "time": "tau"}.get(scale, scale)


def resolve_axis(name, axes):
    """The grid axis `name` means: itself, the prescribed load F0 for its old
    name FN, or its history alias (v1_over_v is w1_over_v, v1 is w1, and
    back); None when there is none."""
    if name in axes:
        return name
    if maps.case_name(name) in axes:
        return maps.case_name(name)
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

    f = open_map(path, h5py, prog)
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
