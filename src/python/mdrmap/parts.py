"""The parts of a case as objects: mdrmap.Material, mdrmap.Indenter and
mdrmap.History, each checked when it is made, with the messages of
mdrmap.simulate (the command line's), and given to mdrmap.simulate and
mdrmap.stationary as material=, indenter=, history=:

    steel = mdrmap.Indenter(R=10)
    rubber = mdrmap.Material(G=1, prony=[(1, 0.1), (2, 10)], aT=0.5)
    shs = mdrmap.History([(1, 2), (0, 100), (1, 5)])
    r = mdrmap.simulate(material=rubber, indenter=steel, history=shs, F0=0.1, v=1)

An object holds its keyword arguments as given (numbers stay the numbers
given: the core gets them as doubles) and what the core read of them (a
file's terms, the WLF shift's constants) as attributes.
"""
import os

from . import _core, _values
from ._core import InvalidInput


class _Part:
    """A part of a case: its keyword arguments and what the core read."""

    _part = ""      # "material", "indenter", "history"
    _options = ()   # the options of the part, as the command line spells them

    def __init__(self, given, origin=None):
        given = {k: v for k, v in given.items() if v is not None}
        keywords = _values.keyword_map(self._options)
        spelled = {}
        name = type(self).__name__
        values = _values.values(given, keywords, name, spelled)
        try:
            read = _core.read_part(values, self._part)
        except InvalidInput as e:
            raise _values.as_keyword(e, spelled) from None
        self._given = given        # keyword -> value, as given
        self._origin = origin      # (constructor name, first argument) of a from_... form
        self._read = read

    def keywords(self):
        """The keyword arguments of mdrmap.simulate this part stands for."""
        return dict(self._given)

    def __eq__(self, other):
        return type(other) is type(self) and self._read == other._read

    def __hash__(self):
        return hash((type(self).__name__, repr(self._read)))

    def __repr__(self):
        args = dict(self._given)
        first = []
        if self._origin is not None:
            method, key = self._origin
            first = [repr(os.fspath(args.pop(key)))]
            name = f"mdrmap.{type(self).__name__}.{method}"
        else:
            name = f"mdrmap.{type(self).__name__}"
            for key in self._positional:
                if key in args:
                    first.append(repr(args.pop(key)))
        return f"{name}({', '.join(first + [f'{k}={v!r}' for k, v in args.items()])})"


class Material(_Part):
    """The foundation's material.

    Material(G=1, tau=1)                          Kelvin: modulus G, relaxation time tau
    Material(G=1, prony=[(G1, tau1), ...])        a Prony spectrum beside the rubbery
                                                  modulus G (tau: the parallel dashpot's
                                                  time, 0 when not given)
    Material(..., aT=0.5)                         shifted by a factor aT, or
    Material(..., temperature=310, wlf=(C1, C2, TREF))   by a temperature and the WLF
                                                  equation (units: "25C", "298.15K";
                                                  allow_large_shift=True beyond 12 decades)
    Material.from_file(path)                      an Abaqus card or pyvisco's CSV
                                                  (material=), or a spectrum CSV
                                                  (prony_file=; with G=, or its column g)

    Attributes (as the core read them): G, tau, aT, prony (the (G, tau)
    terms, a file's too), temperature, wlf and unit where a temperature gave
    aT, notes (what a card gave that does not enter).
    """

    _part = "material"
    _options = ("tau", "G", "aT", "material", "prony", "prony-file", "nu", "T", "wlf",
                "allow-large-shift")
    _positional = ()

    def __init__(self, G=None, tau=None, *, prony=None, aT=None, temperature=None, wlf=None,
                 allow_large_shift=None, T=None, material=None, prony_file=None, nu=None):
        file = {k: v for k, v in (("material", material), ("prony_file", prony_file))
                if v is not None}
        if tau is None and (prony is not None or file):
            tau = 0.0  # a spectrum: no parallel dashpot unless given
        given = dict(file, G=G, tau=tau, prony=prony, aT=aT, temperature=temperature, T=T,
                     wlf=wlf, allow_large_shift=allow_large_shift, nu=nu)
        origin = ("from_file", next(iter(file))) if len(file) == 1 else None
        super().__init__(given, origin)

    @classmethod
    def from_file(cls, path, G=None, tau=None, *, nu=None, **kwargs):
        """A material from a file: an Abaqus card (*ELASTIC, *VISCOELASTIC,
        *TRS) or pyvisco's Prony CSV, or a spectrum CSV with the columns tau
        and G, E (with nu) or g (with '# G0 = ...'); the other keywords as
        Material's."""
        try:
            option = _core.material_file_option(os.fspath(path))
        except TypeError:
            raise _values.InvalidType(f"must be a path (a str or a pathlib.Path), got "
                                      f"{type(path).__name__} {path!r:.60}", "material") from None
        file = {"material": path} if option == "material" else {"prony_file": path}
        return cls(G, tau, nu=nu, **kwargs, **file)

    def __getattr__(self, name):
        read = self.__dict__.get("_read", {})
        if name in ("G", "tau", "aT", "prony", "notes"):
            return read[name]
        if name in ("temperature", "wlf", "unit"):
            return read.get(name)
        raise AttributeError(name)


class Indenter(_Part):
    """The rigid indenter.

    Indenter(R=10)                  the parabola f(r) = r^2 / 2R (the default)
    Indenter("cone", beta=10)       a cone, beta degrees between surface and plane
    Indenter("power", n=3, A=0.5)   a power law f(r) = A r^n

    Attributes: profile and its parameters (R; beta; n, A).
    """

    _part = "indenter"
    _options = ("profile", "R", "beta", "n", "A")
    _positional = ("profile",)

    def __init__(self, profile=None, *, R=None, beta=None, n=None, A=None):
        super().__init__(dict(profile=profile, R=R, beta=beta, n=n, A=A))

    def __getattr__(self, name):
        read = self.__dict__.get("_read", {})
        if name in read:
            return read[name]
        raise AttributeError(name)


class History(_Part):
    """The velocity history after t = 0 (the stationary sliding before it is
    at mdrmap.simulate's v=).

    History([(w1, T1), (w2, T2), ...])   segments of velocity wk >= 0 (0: a hold)
                                         lasting Tk > 0, one after another
    History.from_record(path)            a lab record (CSV with columns t and v):
                                         v0 and the segments from its rows; the
                                         results at its rows (as the CLI's CSV)

    Attributes: segments (the (w, T) pairs), and from a record v (its first
    row's velocity), record (the path) and rows (its number of rows).
    Segment k of the list is the results' segment k and the change at its
    start their event k, both from 0 (the CSV's `segment` column and
    `# event k=`); a study config numbers the same segment k + 1 (wK, TK).
    """

    _part = "history"
    _options = ("history", "history-file")
    _positional = ("history",)

    def __init__(self, segments=None, *, history_file=None):
        if segments is not None and not isinstance(segments, str):
            try:
                segments = [tuple(s) if isinstance(s, (list, tuple)) else s for s in segments]
            except TypeError:
                pass  # (refused by the core's reader, naming history)
        given = dict(history=segments, history_file=history_file)
        super().__init__(given, ("from_record", "history_file") if history_file is not None
                         else None)

    @classmethod
    def from_record(cls, path):
        """The history of a lab record (mdrmap.simulate's history_file=)."""
        return cls(history_file=path)

    @property
    def segments(self):
        return list(self._read["history"])

    def __getattr__(self, name):
        read = self.__dict__.get("_read", {})
        if name in ("v", "record", "rows"):
            return read.get(name)
        raise AttributeError(name)

    def __len__(self):
        return len(self._read["history"])

    def __iter__(self):
        return iter(self._read["history"])


_KINDS = {"material": Material, "indenter": Indenter, "history": History}


def merged(options, allowed):
    """The keyword arguments with each part object (material=, indenter=,
    history=) replaced by the keywords it stands for; a keyword given both
    by an object and by itself is refused naming it. `allowed`: the parts
    the call takes."""
    out = {}
    if "indenter" in options and not isinstance(options["indenter"], _Part):
        raise _values.InvalidType(f"must be a mdrmap.Indenter, got {options['indenter']!r:.60}",
                                  "indenter")
    for key, value in options.items():
        kind = _KINDS.get(key)
        if kind is not None and isinstance(value, _Part):
            if not isinstance(value, kind) or key not in allowed:
                what = f"a mdrmap.{kind.__name__}" if key in allowed else "not taken here"
                raise _values.InvalidType(f"must be {what}, got {value!r:.80}", key)
            continue
        out[key] = value
    for key in allowed:
        value = options.get(key)
        if not isinstance(value, _Part):
            continue
        for k, v in value.keywords().items():
            if k in out:
                raise InvalidInput(f"is given twice: by {key}= ({value!r:.60}) and as a "
                                   "keyword; give it once", k)
            out[k] = v
    return out
