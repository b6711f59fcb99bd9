"""The values of mdrmap.simulate's and mdrmap.stationary's keywords as the
core takes them (mdrmap._core): a number as a float (exactly: never as a
text), a name or a path as a str, history and prony as a list of pairs of
floats, wlf and v-list as a tuple of floats, a flag as a bool; a str where a
number is expected as the command line's text (the core reads it as the CLI
does). A value of the wrong type is refused naming the keyword (InvalidType)."""
import numbers
import os

from . import _core, _doc
from ._core import InvalidInput

# the old spellings the options take, {alias: option}: FN for F0
_ALIASES = _core.parameter_aliases()


def keyword_map(options):
    """keyword -> option: each option under its Python name (and as spelled),
    and the old spelling of a parameter (FN) as itself (the core reads it as
    its parameter's and refuses both)."""
    out = {o.replace("-", "_"): o for o in options}
    out.update({o: o for o in options})
    out.update({alias: alias for alias, name in _ALIASES.items() if name in options})
    out.update({_doc.keyword(o): o for o in options})  # temperature for T
    return out


class InvalidType(InvalidInput, TypeError):
    """A value of the wrong type for its keyword (a bool, bytes or a path
    where a number is expected): an InvalidInput (a ValueError) naming the
    option, and a TypeError."""


# the options that name a file (they take a str or an os.PathLike)
_PATHS = {"prony-file", "history-file", "material"}
# the options whose value is a name (a str)
_NAMES = {"profile", "spacing", "solver"}
# the options that are a flag (a bool, or the command line's text)
_FLAGS = {"allow-large-shift"}
_PAIRS = {"history": ("segment", "(W, T): its velocity W then its duration T"),
          "prony": ("term", "(G, TAU): its modulus G then its relaxation time TAU")}


def _is_bool(value):
    return isinstance(value, bool) or (getattr(getattr(value, "dtype", None), "kind", "") == "b"
                                       and getattr(value, "ndim", None) == 0)


def _not_a_number(option, value):
    """The refusal of a value that is not a number where one is expected."""
    if _is_bool(value):
        return InvalidType(f"must be a number, got {bool(value)}", option)
    if isinstance(value, (bytes, bytearray, memoryview)):
        return InvalidType(f"must be a number, got {type(value).__name__} "
                           f"{bytes(value)[:60]!r}", option)
    if isinstance(value, os.PathLike):
        return InvalidType(f"must be a number, got a path {os.fspath(value)[:60]!r}", option)
    text = repr(value)
    text = text if len(text) <= 60 else text[:60] + "..."
    return InvalidType(f"must be a number, got {type(value).__name__} {text}", option)


def number(option, value):
    """A number as the float the core takes (exactly: a float as it is, an
    int rounded once, numpy's scalars as their value); a str as the text the
    command line takes (the core reads it as the CLI does)."""
    kind = type(value)
    if kind is float or kind is str:  # the common cases first
        return value
    if value is None:
        raise InvalidInput(f"needs a value, e.g. {option.replace('-', '_')}=1.5", option)
    if _is_bool(value) or not isinstance(value, numbers.Real) and \
            not (getattr(getattr(value, "dtype", None), "kind", "-") in ("f", "i", "u")
                 and getattr(value, "ndim", None) == 0):
        raise _not_a_number(option, value)
    try:
        return float(value)
    except OverflowError:
        raise InvalidInput(f"must be a finite number, got {value} (too large for a double)",
                           option) from None


def _text(option, value):
    """A name or a path: a str (a path may be an os.PathLike)."""
    if isinstance(value, str):
        return value
    if option in _PATHS and isinstance(value, os.PathLike):
        return os.fspath(value)
    if value is None:
        raise InvalidInput(f"needs a value, e.g. {option.replace('-', '_')}=...", option)
    what = "a path (a str or a pathlib.Path)" if option in _PATHS else "a str"
    raise InvalidType(f"must be {what}, got {type(value).__name__} {value!r:.60}", option)


def _pairs(option, value):
    """history [(w1, T1), (w2, T2), ...], prony [(G1, tau1), ...]: a list of
    pairs of floats (a str as the command line's text)."""
    if isinstance(value, str) or value is None:
        return number(option, value)
    item, pair = _PAIRS[option]
    try:
        items = list(value)
    except TypeError:
        raise InvalidType(f"must be a list of {item}s {pair.split(':')[0]}, got {value!r}",
                          option) from None
    out = []
    for k, it in enumerate(items, 1):
        try:
            a, b = it
        except (TypeError, ValueError):
            raise InvalidType(f"{item} {k} must be a pair {pair}, got {it!r}", option) from None
        out.append((number(option, a), number(option, b)))
    if any(isinstance(x, str) for p in out for x in p):  # texts: as the command line's
        return ",".join(f"{a}:{b}" for a, b in out)
    return out


def _wlf(value):
    """wlf=(C1, C2, TREF): a tuple of floats (a str as it is; a TREF with a
    unit, "298.15K", makes the whole a text)."""
    if isinstance(value, str) or value is None:
        return number("wlf", value)
    try:
        items = list(value)
    except TypeError:
        items = None
    if items is None or len(items) != 3:
        raise InvalidInput(f"must be the three WLF constants (C1, C2, TREF), got {value!r}",
                           "wlf")
    x = tuple(number("wlf", c) for c in items)
    return ":".join(str(c) for c in x) if any(isinstance(c, str) for c in x) else x


def _flag(option, value):
    if _is_bool(value):
        return bool(value)
    if isinstance(value, str):
        return value
    raise InvalidType(f"must be True or False (a flag), got {value!r:.60}", option)


def convert(option, value):
    """The value the core takes for an option (mdrmap._core: a float, a str,
    a bool, a tuple of floats or a list of pairs of floats)."""
    if option in _PATHS or option in _NAMES:
        return _text(option, value)
    if option in _PAIRS:
        return _pairs(option, value)
    if option == "wlf":
        return _wlf(value)
    if option in _FLAGS:
        return _flag(option, value)
    return number(option, value)  # (T: a str may carry a unit, "25C")


def values(kwargs, keywords, function, spelled=None):
    """{option: value} of the keyword arguments; `spelled` gets {option:
    keyword} where the keyword is not the option's spelling (temperature)."""
    texts = {}
    spelled = {} if spelled is None else spelled
    for key, v in kwargs.items():
        option = keywords.get(key)
        if option is None:
            names = ", ".join(k for k in keywords if "-" not in k)
            raise InvalidInput(f"not a keyword of mdrmap.{function} (keywords are "
                               f"case-sensitive: {names}), got {key}", key)
        if option in texts:
            raise InvalidInput("may be given only once", option)
        if key != option and key == _doc.keyword(option):
            spelled[option] = key
        try:
            texts[option] = convert(option, v)
        except InvalidInput as e:
            raise as_keyword(e, spelled) from None
    return texts


def as_keyword(e, spelled):
    """e naming the keyword its option was given under (temperature for T)."""
    if e.option in spelled:
        e.keyword = spelled[e.option]
        e.args = (f"{e.keyword}: {e.message}",)
    return e
