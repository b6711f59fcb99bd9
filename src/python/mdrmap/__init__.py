"""mdrmap from Python: the solvers, the events and the maps.

    import mdrmap
    r = mdrmap.simulate(d=0.1, R=10, tau=1, v=2, v1=0.5)     # one step
    r = mdrmap.simulate(F0=0.1, R=10, tau=1, v=1,             # load control
                        history=[(0.1, 20), (1, 20)], samples=101)
    r.t, r.mu, r.FN, r.Fx, r.a2        # numpy arrays (r.d, r.a1 under load)
                                       # (FN: the measured normal force)
    r.events[0]["a_minus_b"], r.pre["mu"], r.info["error_estimate"]

The keyword arguments are `mdrmap simulate`'s options (mdrmap.parameters()
lists those of the parameter table: the loading d or F0, the indenter's R,
beta, n, A, the material's tau, G, aT, the velocity v and the sampling),
with '_' for '-' (t_end, log_decades), and the same checks and messages:
bad input raises InvalidInput (a ValueError) naming the option. Numbers are
given as Python or numpy numbers, which reach the solvers as those doubles
(or as the text the command line takes); a value of the wrong type raises
InvalidType (an InvalidInput and a TypeError); the history as a list of
(w, T) pairs (or "W1:T1,W2:T2"), a spectrum as prony=[(G, tau), ...], the
WLF constants as wlf=(C1, C2, TREF) with temperature= (T= its old spelling).
FN= is accepted as the old spelling of the prescribed load F0= (not both).
The parts of a case may be given as objects, checked when made:
material=mdrmap.Material(G=1, tau=1), indenter=mdrmap.Indenter(R=10),
history=mdrmap.History([(0.1, 20), (1, 20)]) (mdrmap.parts).
help(mdrmap.simulate) lists every keyword. The results equal the command
line's bit for bit; the solver runs without the GIL, so a thread pool over
cases uses every core; Ctrl-C raises KeyboardInterrupt within a fraction of
a second, and progress=callable reports how far a call got.
"""

import os
import sys

try:
    from . import _core
except ImportError as _error:  # not built (for this Python), or does not load
    import importlib.machinery
    _here = __path__[0]
    _why = "is not built for Python %d.%d in %s" % (sys.version_info[:2] + (_here,))
    if any(os.path.exists(os.path.join(_here, "_core" + s))
           for s in importlib.machinery.EXTENSION_SUFFIXES):
        _why = "in %s does not load (%s)" % (_here, _error)
    raise ImportError("mdrmap: the extension mdrmap._core " + _why + ": build it with "
                      "`cmake --build build --target mdrmap_python` and set "
                      "PYTHONPATH=build/python, or install with "
                      "`pip install --no-build-isolation --no-index .`") from None
from ._core import InvalidInput
from .maps import MapError, open_map, to_grid
from . import _doc, _values
from ._values import InvalidType
from .parts import History, Indenter, Material
from . import parts as _parts

__version__ = _core.__version__
__all__ = ["simulate", "stationary", "fit", "parameters", "open_map", "to_grid", "Result",
           "Material", "Indenter", "History", "InvalidType",
           "InvalidInput", "MapError"]

# the options as the command line spells them -> the keyword of each
_OPTIONS = _core.option_names()
_TABLE = _core.parameter_table()
_OUTPUTS = _core.output_table()  # every output quantity's one name (the CSV's, the map's)
# the old spellings the options take, {alias: option}: FN for F0
_ALIASES = _core.parameter_aliases()
_INTEGER = {p["name"] for p in _TABLE if p["unit"] == "count"}
# the case's parameters without history and sampling, and its spectrum and temperature
_STATIONARY = [p["name"] for p in _TABLE if not p["sampling"]] + \
    [o for o in ("profile", "material", "prony", "prony-file", "nu", "T", "wlf",
                    "allow-large-shift") if o in _OPTIONS]


_SIMULATE_KEYWORDS = _values.keyword_map(_OPTIONS)
_STATIONARY_KEYWORDS = _values.keyword_map(_STATIONARY)


def _call(function, texts, progress, spelled):
    """_core.function(texts, progress); an InvalidInput of an option given
    under another keyword (temperature= for T) names that keyword."""
    if progress is not None and not callable(progress):
        raise TypeError(f"progress must be a callable (or None), got {progress!r}")
    try:
        return function(texts, progress)
    except InvalidInput as e:
        if e.option not in spelled:
            raise
        raise _values.as_keyword(e, spelled) from None


class Result:
    """One case's result (mdrmap.simulate).

    t, segment, FN, Fx, mu, a2   numpy arrays, one value per sample (segment
                                 after segment; t since the first change;
                                 segment k from 0, as the CSV's column: the
                                 history's k-th pair, a study config's
                                 segment k + 1); under load (F0=) also d and
                                 a1; a lab record's run (history_file=) has
                                 one sample per record row, as the CSV, and
                                 v (the row's velocity) and slip
    events   one dict per velocity change k, the change into segment k (the
             CSV's `# event k=` line, k from 0): k, t,
             w_before, w_after, mu_before, mu_after, mu_max, t_max, slip_max,
             mu_min, t_min, slip_min, mu_peak, t_peak, slip_peak, mu_end,
             mu_ss_before, mu_ss_after, D_c, overshoot, a, a_minus_b, b,
             healing (nan where undefined), and where D_c is nan
             D_c_undefined, why: no_change, hold, no_transient, peak_at_end,
             overshoot or no_decay (docs/design.md, "Event metrics")
    pre      the stationary state before t = 0: FN, Fx, mu, a2 (d, a1 under load)
    (Every name is the output table's, mdrmap._core.output_table(), as in
    the CSV and the map: docs/reference/map-schema.md, "Output quantities".)
    info     solver, rtol, error_estimate, cells_per_a1, elements, steps,
             element_updates, root_solves, wall_seconds, version, commit
             (error_vs_exact, or error_vs_reference/reference/reference_rtol,
             as the CSV gives them)
    case     the case as run (the CSV's `# case` line): its parameters, the
             history as (w, T) pairs (the default window resolved), spacing,
             a0 under load, zeta0; prony as (G, tau) pairs where the
             material has a spectrum
    scales   the case's scales (the CSV's `# scales` line, the map's /scales):
             length, depth, force, friction, time

    to_dataframe() gives the samples as a pandas DataFrame, to_xarray() as an
    xarray Dataset (the columns of the CSV, one row per sample).
    """

    def __init__(self, fields):
        self.__dict__.update(fields)

    @property
    def load(self):
        """Whether the case is load-controlled (F0 given)."""
        return "F0" in self.case

    @property
    def record(self):
        """Whether a lab record (history_file=) gave the history: then one
        sample per record row, with its v and slip."""
        return self.case.get("sampling") == "record"

    @property
    def columns(self):
        """The names of the per-sample arrays, in the CSV's order: t, segment,
        FN, Fx, mu, a2 (and d, a1 under load; v, slip of a lab record)."""
        return [o["name"] for o in _OUTPUTS if o["group"] == "series" and o["csv"] and
                (self.load or not o["load_only"])] + (["v", "slip"] if self.record else [])

    def _attrs(self):
        return {"case": dict(self.case), "pre": dict(self.pre), "scales": dict(self.scales),
                "info": dict(self.info), "events": [dict(e) for e in self.events]}

    def to_dataframe(self):
        """The samples as a pandas DataFrame: one row per sample, the columns
        of `columns` (the CSV's); .attrs holds case, pre, scales, info and
        events (copies). Raises ImportError (one line) without pandas."""
        try:
            import pandas
        except ImportError:
            raise ImportError("mdrmap.Result.to_dataframe needs pandas, which this Python "
                              "cannot import (pip install pandas; Debian: apt-get install "
                              "python3-pandas); Result.to_xarray() gives an xarray Dataset, "
                              "the arrays r.t, r.mu, ... need neither") from None
        df = pandas.DataFrame({name: getattr(self, name) for name in self.columns})
        df.attrs.update(self._attrs())
        return df

    def to_xarray(self):
        """The samples as an xarray Dataset over the dimension `sample`: t
        and segment as coordinates, the other columns as variables; .attrs
        holds case, pre, scales, info and events (copies). Raises ImportError
        (one line) without xarray."""
        try:
            import xarray
        except ImportError:
            raise ImportError("mdrmap.Result.to_xarray needs xarray, which this Python cannot "
                              "import (pip install xarray; Debian: apt-get install "
                              "python3-xarray)") from None
        coords = {name: ("sample", getattr(self, name)) for name in ("t", "segment")}
        data = {name: ("sample", getattr(self, name)) for name in self.columns
                if name not in coords}
        return xarray.Dataset(data, coords=coords, attrs=self._attrs())

    def __repr__(self):
        return (f"<mdrmap.Result {self.t.size} samples, {len(self.events)} events, "
                f"solver={self.info['solver']}, mu_pre={self.pre['mu']:.6g}>")


def simulate(*, progress=None, **options):
    options = _parts.merged(options, ("material", "indenter", "history"))
    spelled = {}
    texts = _values.values(options, _SIMULATE_KEYWORDS, "simulate", spelled)
    return Result(_call(_core.simulate, texts, progress, spelled))


simulate.__doc__ = _doc.docstring(
    "Runs one case as `mdrmap simulate` does and returns a Result.\n\n"
    "The keywords are the command line's options with '_' for '-'; numbers as\n"
    "Python or numpy numbers (or the text the command line takes).",
    _doc.entries(_OPTIONS, _TABLE, _ALIASES) + _doc.PARTS + [("progress", _doc.PROGRESS)],
    "Raises InvalidInput (bad input, as the CLI's exit code 2), RuntimeError\n"
    "(the case cannot be computed within its budget or rtol, exit code 1).")


def fit(*, data, free, bounds=(), starts=1, threads=None, **options):
    """Fits case parameters to lab records as `mdrmap fit` does (docs/fitting.md).

    data: a record file or a list of them; free: "R,aT" or ["R", "aT"];
    bounds: {"R": (lo, hi)} or ["R=LO:HI", ...]; starts: Levenberg-Marquardt
    runs from the best pre-search points (1 to 25); threads: how many threads
    share a batch of evaluations (default: os.cpu_count()); the other
    keywords are the case's, as for simulate, their values the start.
    Returns a dict: parameters {NAME: {value, stderr, ci95, at_bound}},
    undetermined (names in a direction the records do not fix; their values
    carry no interval, nan), correlation {names, matrix}, rms, sigma,
    residuals, evaluations, batches, iterations, converged, rtol, step.
    Raises InvalidInput as the CLI's exit code 2."""
    import os
    data = [data] if isinstance(data, (str, bytes, os.PathLike)) else list(data)
    free = [free] if isinstance(free, str) else [",".join(free)]
    if isinstance(bounds, dict):
        bounds = [f"{k}={lo!r}:{hi!r}" for k, (lo, hi) in bounds.items()]
    threads = (os.cpu_count() or 1) if threads is None else int(threads)
    options = _parts.merged(options, ("material", "indenter"))
    spelled = {}
    values = _values.values(options, _SIMULATE_KEYWORDS, "fit", spelled)
    try:
        return _core.fit(values, [os.fspath(d) for d in data], free, list(bounds), str(starts),
                         threads)
    except InvalidInput as e:
        if e.option not in spelled:
            raise
        raise _values.as_keyword(e, spelled) from None


def stationary(*, progress=None, **options):
    options = _parts.merged(options, ("material", "indenter"))
    v = options.get("v")
    many = v is not None and not isinstance(v, (str, bytes)) and \
        (getattr(v, "ndim", None) or 0) > 0 or isinstance(v, (list, tuple, range))
    if many:
        options = dict(options)
        del options["v"]
    spelled = {}
    texts = _values.values(options, _STATIONARY_KEYWORDS, "stationary", spelled)
    if many:
        texts["v-list"] = tuple(_values.number("v", x) for x in v)
        if any(isinstance(x, str) for x in texts["v-list"]):
            texts["v-list"] = ",".join(str(x) for x in texts["v-list"])
        spelled["v-list"] = "v"
    out = _call(_core.stationary, texts, progress, spelled)
    if many:
        return out
    del out["v"]
    return {name: float(x[0]) for name, x in out.items()}


stationary.__doc__ = _doc.docstring(
    "The stationary sliding state (FN, Fx, mu, a2, and d, a1 under load) of a\n"
    "case without its history, as `mdrmap stationary` gives it: at v= a dict\n"
    "of numbers (the state events[0][\"mu_ss_before\"] of simulate describes),\n"
    "at v=[v1, v2, ...] (a list or an array, as --v-list) a dict of numpy\n"
    "arrays, one value per velocity, with v itself.",
    [(k, t) if k != "v" else ("v", t + "; or a list or array of velocities")
     for k, t in _doc.entries(_STATIONARY, _TABLE, _ALIASES)] +
    _doc.PARTS + [("progress", _doc.PROGRESS)],
    "Raises InvalidInput (bad input, as the CLI's exit code 2).")


def parameters():
    """The parameter table, one dict per parameter in the table's order
    (`mdrmap simulate --help-all` groups them by part): name (option),
    keyword, symbol, unit, range, meaning, required, one_of (group or
    None), profile (the indenter profile it belongs to, for which alone it
    is required, or None: every profile), default (None if required or in a
    group), sampling (a sampling parameter) and help (the CLI's text)."""
    out = []
    for p in _TABLE:
        q = dict(p)
        q["keyword"] = p["name"].replace("-", "_")
        out.append(q)
    return out
