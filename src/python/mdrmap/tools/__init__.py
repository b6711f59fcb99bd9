"""The post-processing tools of mdrmap, run as `python -m mdrmap TOOL ...`
(mdrmap/__main__.py) or `python -m mdrmap.tools.TOOL ...`.

Each tool is a module here with main(argv) (its argparse front end, bad
input one line on stderr and exit code 2) and PROG; the map tools read maps
with the package's map reader (mdrmap.maps, through _maplib), the history
tools compute their runs with mdrmap.simulate in this process (_runs).
"""
import importlib

# name -> what it does (one line of `python -m mdrmap --help`), in that order
TOOLS = {
    "plot_run": "one run's friction and FN or depth against t or slip (simulate or a CSV)",
    "steps": "velocity-step responses and rate-and-state numbers of one case",
    "healing": "healing in slide-hold-slide runs of one case over hold times",
    "plot_fit": "the records of mdrmap fit with the fitted model and residuals",
    "map_summary": "what a map holds; its rows as CSV",
    "plot_map": "colour map of map quantities over two parameters",
    "plot_timeseries": "a map's responses to velocity changes (time series)",
    "map_steps": "step responses in scaled variables from a map's time series",
    "map_healing": "the healing curve of a slide-hold-slide map",
    "map_rate_state": "maps of the apparent a, b, a - b and D_c of one event",
    "map_friction_velocity": "stationary friction against velocity of a map under load",
    "map_master_curve": "the master curve of a map over velocity and temperature",
    "mapxr": "a map as an xarray Dataset (a grid study as N dimensions)",
}


def tool_name(text):
    """The tool TEXT names (plot-map for plot_map too), or None."""
    name = text.replace("-", "_")
    return name if name in TOOLS else None


def load(name):
    """The module of tool NAME."""
    return importlib.import_module("." + name, __name__)


def run(name, argv):
    """Runs tool NAME with the arguments ARGV; its exit code (a UserError:
    one line on stderr and 2)."""
    from ._maplib import run_tool
    module = load(name)
    return run_tool(lambda: module.main(argv), module.PROG)
