"""The docstrings of mdrmap.simulate and mdrmap.stationary, generated from
the parameter table (_core.parameter_table: meaning, unit, range, default),
the help of the other options (_core.option_help: the command line's texts,
in Python's words) and the command line's option list (_core.option_names),
so that they list every keyword the calls take
(tests/python/test_arguments.py checks it)."""
import re
import textwrap

from . import _core

# the value of an option where Python takes another than the command line's
# text (which it also takes): "VALUE: " before the option's text
PYTHON_VALUE = {
    "prony": '[(G1, tau1), (G2, tau2), ...] (or "G1:TAU1,G2:TAU2,...")',
    "prony-file": "a file (a str or a path)",
    "material": "a mdrmap.Material (its keywords: G, tau, prony, aT, temperature, ...), "
                "or a file (a str or a path)",
    "wlf": '(C1, C2, TREF) (or "C1:C2:TREF")',
    "allow-large-shift": "True",
    "history": 'a mdrmap.History, or [(w1, T1), (w2, T2), ...] (or "W1:T1,W2:T2,...")',
    "history-file": "a file (a str or a path)",
}
# the parts of a case as objects (mdrmap.parts), keywords beside the options
PARTS = [("indenter", "a mdrmap.Indenter: the profile and its parameters (instead of profile, "
                      "R, beta, n, A)")]
# keywords that are not the option with '_' for '-'
KEYWORD = {"T": "temperature"}
PROGRESS = ("a callable, called from the calling thread with the fraction of the "
            "samples done (a solver that refines starts again from 0), at most "
            "about every 0.2 s, and with 1.0 when the call succeeded; an exception "
            "it raises stops the call. Ctrl-C raises KeyboardInterrupt within a "
            "fraction of a second")
UNDOCUMENTED = "(undocumented)"


def keyword(option):
    return KEYWORD.get(option, option.replace("-", "_"))


def _python_words(text):
    """The command line's text with keywords for its options (--T: temperature)."""
    return re.sub(r"--([A-Za-z][A-Za-z0-9-]*)", lambda m: keyword(m.group(1)), text)


def _option_text(option):
    """The text of an option outside the table, from the command line's
    (_core.option_help), in Python's words."""
    h = _core.option_help().get(option)
    if h is None:
        return UNDOCUMENTED
    text = _python_words(h["text"])
    if option in PYTHON_VALUE:
        text = f"{PYTHON_VALUE[option]}: {text}"
    if h["default"] is not None:
        text += f". Default: {_python_words(h['default'])}"
    if option in KEYWORD:  # temperature for T
        text += f"; {option}= is accepted as its old spelling"
    return text


def _table_text(p, table, aliases):
    if p["required"]:
        need = "required"
    elif p["one_of"]:
        need = "give one of " + " or ".join(q["name"] for q in table
                                            if q["one_of"] == p["one_of"])
    else:
        need = f"default {p['default']:g}"
    text = f"{_python_words(p['meaning'])} ({p['unit']}; {p['range']}; {need})"
    old = [a for a, name in aliases.items() if name == p["name"]]
    return text + "".join(f"; {a}= is accepted as its old spelling" for a in old)


def entries(options, table, aliases):
    """(keyword, text) of each option, in the order given."""
    params = {p["name"]: p for p in table}
    out = []
    for o in options:
        if o in params:
            out.append((keyword(o), _table_text(params[o], table, aliases)))
        else:
            out.append((keyword(o), _option_text(o)))
    return out


def keyword_list(items, width=79):
    lines = []
    for kw, text in items:
        head = f"    {kw:<13}" if len(kw) < 13 else f"    {kw} "  # a long keyword: one space
        lines += textwrap.wrap(text, width, initial_indent=head, subsequent_indent=" " * 17)
    return "\n".join(lines)


def docstring(head, items, tail):
    return f"{head}\n\nKeyword arguments (from the parameter table and the command line's " \
           f"help):\n{keyword_list(items)}\n\n{tail}"
