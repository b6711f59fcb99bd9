"""Shared by the map tools (plot_map, plot_timeseries, map_summary): opening an
mdrmap friction map with clear one-line errors.

Not a script: the tools import it from their own directory.
"""
import argparse
import os
import sys

SCHEMA = "mdrmap-map/1"
# The /cases columns of maps written before /schema (the fallback of case_columns)
CASE_COLS = ["d", "R", "tau", "v", "v1", "G"]


class UserError(Exception):
    """A problem with the input: reported in one line, exit code 2."""


class Parser(argparse.ArgumentParser):
    def error(self, message):  # one line instead of usage + message
        raise UserError(f"{message} (see --help)")


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


def open_map(path, h5py, prog):
    """Opens PATH read-only; UserError unless it is a readable mdrmap map."""
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
    schema = text(f.attrs["mdrmap_schema"])
    if schema != SCHEMA:
        print(f"{prog}: warning: {path} has schema {schema}; this tool reads {SCHEMA}",
              file=sys.stderr)
    for need in ["results/status"] + [f"cases/{c}" for c in CASE_COLS[:5]]:
        if need not in f:
            f.close()
            raise UserError(f"{path} is an incomplete mdrmap map (no /{need})")
    return f


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
    """The /cases columns of an open map: those /schema lists (map order) when the
    map has it, else CASE_COLS. `described`: schema(f), when already read."""
    described = schema(f) if described is None else described
    cols = [p.split("/", 1)[1] for p in described if p.startswith("cases/")]
    return [c for c in cols if f"cases/{c}" in f] or list(CASE_COLS)


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
