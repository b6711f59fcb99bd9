"""The docstrings of mdrmap.simulate and mdrmap.stationary, generated from
the parameter table (_core.parameter_table: meaning, unit, range, default)
and the command line's option list (_core.option_names), so that they list
every keyword the calls take (tests/python/test_arguments.py checks it)."""
import textwrap

# the options that are not parameters of the table, as the keywords take them
OTHER = {
    "profile": 'the indenter: "parabola" (the default; R), "cone" (beta) or '
               '"power" (n, A)',
    "prony": "a relaxation spectrum, the Maxwell branches beside G: [(G1, tau1), "
             '(G2, tau2), ...] (or "G1:TAU1,G2:TAU2,..."), at most 32 terms; with a '
             "spectrum G (required) is the rubbery modulus and tau the parallel dashpot's time "
             "(0: none)",
    "prony-file": "the spectrum from a CSV file (a str or a path): a header naming "
                  "the columns, tau and one of G (shear moduli), E (Young's moduli) or g "
                  "(normalised by a line '# G0 = VALUE', then G = G0 (1 - sum g)), then "
                  "one term per line; not with prony",
    "material": "a mdrmap.Material (its keywords: G, tau, prony, aT, temperature, ...), "
                "or the material from an Abaqus card (a str or a path): *ELASTIC E, nu, "
                "*VISCOELASTIC, TIME=PRONY g_i, k_i, tau_i and *TRS, DEFINITION=WLF "
                "Tref, C1, C2; instead of G, prony, prony_file and wlf",
    "nu": "Poisson's ratio of a spectrum file's Young's moduli (column E): "
          "G = E / (4 (1 - nu^2)), -1 < nu <= 0.5, default 0.5",
    "T": "the temperature: with wlf, gives the shift factor aT by the WLF equation "
         "(instead of aT); a finite number > TREF - C2, with an optional unit "
         '("25C", "298.15K"; converted to TREF\'s unit; a bare number is in the '
         "other's unit). A shift of more than 12 decades is refused unless "
         "allow_large_shift=True. T= is accepted as its old spelling",
    "allow-large-shift": "True: take a temperature's WLF shift of more than 12 "
                         "decades from 1 (refused otherwise: most often a C/K mix-up)",
    "wlf": "the WLF constants of temperature, (C1, C2, TREF) (or "
           '"C1:C2:TREF"): log10 aT = -C1 (T - TREF) / (C2 + T - TREF), C1 > 0, '
           "C2 > 0, TREF the reference temperature (aT = 1), with an optional unit "
           '(8.86, 101.6, "25C")',
    "v1": "one step: the sliding velocity from t = 0 on (length/time), >= 0; "
          "0 stops the indenter",
    "t-end": "with v1: how long the step is followed (time), > 0; default 6 tau "
             "(with a spectrum 6 aT max(tau, tauk))",
    "history": "a mdrmap.History, or segments one after another from t = 0: "
               "[(w1, T1), (w2, T2), ...] "
               '(or "W1:T1,W2:T2,..."), velocity wk >= 0 (0: a hold) for the '
               "duration Tk > 0; give v1 or history",
    "history-file": "a lab record (a str or a path): CSV with a header naming the "
                    "columns t and v (the load-point velocity), other columns ignored; "
                    "v0 is the first row's v, t = 0 the first row's time, a segment "
                    "starts at each change of v and the samples are at the rows' "
                    "times (each segment's end too, the instant of the next one's "
                    "start); not with v, v1, t_end, history or the sampling",
    "spacing": '"linear" (the default) or "log" (log_decades): where the samples '
               "of a segment lie",
    "rtol": "target accuracy: bound on the case error, in (0, 0.1]; default 1e-4",
    "solver": '"auto" (the default: the cheapest that meets rtol), "exact", "mdr", '
              '"baseline" or "spectrum"',
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


def _table_text(p, table, aliases):
    if p["required"]:
        need = "required"
    elif p["one_of"]:
        need = "give one of " + " or ".join(q["name"] for q in table
                                            if q["one_of"] == p["one_of"])
    else:
        need = f"default {p['default']:g}"
    text = f"{p['meaning']} ({p['unit']}; {p['range']}; {need})"
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
            out.append((keyword(o), OTHER.get(o, UNDOCUMENTED)))
    return out


def keyword_list(items, width=79):
    lines = []
    for kw, text in items:
        head = f"    {kw:<13}" if len(kw) < 13 else f"    {kw} "  # a long keyword: one space
        lines += textwrap.wrap(text, width, initial_indent=head, subsequent_indent=" " * 17)
    return "\n".join(lines)


def docstring(head, items, tail):
    return f"{head}\n\nKeyword arguments (generated from the parameter table):\n" \
           f"{keyword_list(items)}\n\n{tail}"
