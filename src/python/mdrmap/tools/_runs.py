"""Shared by the history tools (steps, healing): the runs of one case,
computed in this process by mdrmap.simulate (or read back from CSVs in the
format of `mdrmap simulate`), with one-line errors.

A CSV is the program's output (`mdrmap simulate --help-all`, "Output"): comment
lines `# mdrmap ...`, `# case ...`, `# scales ...`, one `# event ...` per
segment, `# pre ...`, then the header and the rows. With --csv-dir the tools
keep every run there in that format (write_csv), and --from-csv reads them
back (or CSVs that `mdrmap simulate --output` wrote under the same names).

The scales the tools measure by (the reference length a0 or a1, depth,
force, friction a/R, time) are mdrmap's own: Result.scales (the CSV's
`# scales` line, the map's /scales). probe_scales() takes them from a short
run of the case before the tools choose their velocities. Nothing here
computes a scale.

Not a tool: the tools of the package (mdrmap.tools) import it.
"""
import math
import os

from ._maplib import UserError

LOAD_HEADER = "t,segment,FN,Fx,mu,a2,d,a1"  # FN: the measured normal force
DEPTH_HEADER = "t,segment,FN,Fx,mu,a2"
# the old names of case parameters -> today's: the prescribed load F0 was FN
# in the `# case` line of an earlier mdrmap (and in the tools' scales.txt)
CASE_ALIASES = {"FN": "F0"}
# the `# case` fields that are words, not numbers (the indenter's profile)
WORDS = ("profile",)


def case_names(d):
    """A `# case` line's dict under today's names (F0 for an old CSV's FN)."""
    return {CASE_ALIASES.get(k, k) if CASE_ALIASES.get(k, k) not in d else k: v
            for k, v in d.items()}


def fields(line):
    """`key=value` tokens of a comment line as a dict of strings."""
    out = {}
    for tok in line.split()[1:]:
        if "=" in tok:
            key, value = tok.split("=", 1)
            out[key] = value
    return out


def number(text, what):
    try:
        return float(text)
    except ValueError:
        raise UserError(f"{what}: not a number: {text!r}") from None


class Run:
    """One run: case, pre state, events, columns (numpy arrays), history
    [(w, T), ...] and scales {length, depth, force, friction, time}."""

    def __init__(self, path, case, pre, events, columns, load, history, scales):
        self.path, self.case, self.pre, self.events = path, case, pre, events
        self.col, self.load, self.hist, self.sc = columns, load, history, scales

    def scales(self):
        """(length, depth, friction) of the case: mdrmap's scales (a0, d0,
        a0/R under load, a1, d, a1/R at fixed depth)."""
        return self.sc["length"], self.sc["depth"], self.sc["friction"]

    def history(self):
        return self.hist

    def segment(self, k):
        """Boolean mask of segment k's rows."""
        return self.col["segment"] == k


def pairs(text, what):
    """"A:B,C:D" as [(A, B), (C, D)] of numbers; UserError naming WHAT."""
    out = []
    for part in text.split(","):
        xy = part.split(":")
        if len(xy) != 2:
            raise UserError(f"{what}: not a list of pairs X:Y, got {text!r}")
        out.append(tuple(number(x, what) for x in xy))
    return out


def read_csv(path, np):
    """Parses an mdrmap simulate CSV; UserError (one line) for anything else."""
    if not os.path.exists(path):
        raise UserError(f"no such file: {path}")
    if os.path.isdir(path):
        raise UserError(f"{path} is a directory, not an mdrmap simulate CSV")
    try:
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
    except (OSError, UnicodeDecodeError) as e:
        raise UserError(f"cannot read {path}: {getattr(e, 'strerror', None) or e}") from None
    comments = [ln for ln in lines if ln.startswith("#")]
    body = [ln for ln in lines if ln and not ln.startswith("#")]
    if not comments or not comments[0].startswith("# mdrmap ") or not body:
        raise UserError(f"{path} is not an mdrmap simulate CSV (no '# mdrmap' line or no rows)")
    header = body[0]
    if header not in (LOAD_HEADER, DEPTH_HEADER):
        raise UserError(f"{path}: unexpected CSV header {header!r}")
    names = header.split(",")
    case_lines = [ln for ln in comments if ln.startswith("# case ")]
    pre_lines = [ln for ln in comments if ln.startswith("# pre ")]
    if len(case_lines) != 1 or len(pre_lines) != 1:
        raise UserError(f"{path}: needs one '# case' and one '# pre' line")
    case_text = case_names(fields(case_lines[0]))
    case = {k: v if k in WORDS else number(v, f"{path}: {k}") for k, v in case_text.items()
            if k not in ("history", "spacing", "prony")}
    if "history" not in case_text:
        raise UserError(f"{path}: its '# case' line has no history")
    scale_lines = [ln for ln in comments if ln.startswith("# scales ")]
    if len(scale_lines) != 1:
        raise UserError(f"{path}: no '# scales' line (written by an mdrmap older than these "
                        f"tools: rerun without --from-csv)")
    scales = {k: number(v, f"{path}: scales {k}") for k, v in fields(scale_lines[0]).items()}
    pre = {k: number(v, f"{path}: pre {k}") for k, v in fields(pre_lines[0]).items()}
    # (every field a number, but D_c_undefined: why D_c is nan, a word)
    events = [{k: v if k == "D_c_undefined" else number(v, f"{path}: event {k}")
               for k, v in fields(ln).items()}
              for ln in comments if ln.startswith("# event ")]
    try:
        data = np.array([[float(x) for x in ln.split(",")] for ln in body[1:]], dtype=float)
    except ValueError:
        raise UserError(f"{path}: a row is not numbers") from None
    if data.ndim != 2 or data.shape[0] == 0 or data.shape[1] != len(names):
        raise UserError(f"{path}: rows do not have the {len(names)} columns of the header")
    run = Run(path, case, pre, events, {n: data[:, i] for i, n in enumerate(names)},
              header == LOAD_HEADER, pairs(case_text["history"], f"{path}: history"), scales)
    run.prony = pairs(case_text["prony"], f"{path}: prony") if "prony" in case_text else []
    return run


def from_result(r, name):
    """A Run of an mdrmap.simulate Result."""
    names = (LOAD_HEADER if r.load else DEPTH_HEADER).split(",")
    case = {k: float(v) if isinstance(v, (int, float)) else v for k, v in r.case.items()
            if k not in ("history", "prony", "spacing")}
    return Run(name, case, dict(r.pre), list(r.events), {n: getattr(r, n) for n in names},
               r.load, [tuple(p) for p in r.case["history"]], dict(r.scales))


def _value(v):
    """A value of a comment line as the program writes it (W:T,... for pairs)."""
    if isinstance(v, (list, tuple)):
        return ",".join(f"{float(a)!r}:{float(b)!r}" for a, b in v)
    if isinstance(v, float):
        return repr(v)
    return str(v)


def write_csv(r, path, tool):
    """Writes the Result r to PATH in the format of `mdrmap simulate` (what
    read_csv and the program's readers take)."""
    info = " ".join(f"{k}={_value(v)}" for k, v in r.info.items()
                    if k not in ("version", "commit"))
    line = lambda kind, d: f"# {kind} " + " ".join(  # noqa: E731
        f"{k}={_value(v)}" for k, v in d.items())
    names = (LOAD_HEADER if r.load else DEPTH_HEADER).split(",")
    columns = [getattr(r, n) for n in names]
    tmp = path + ".part"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(f"# mdrmap {r.info.get('version', '?')} ({r.info.get('commit', '?')}) simulate "
                f"{info} written_by=mdrmap.simulate,{tool}\n")
        f.write(line("case", r.case) + "\n")
        f.write(line("scales", r.scales) + "\n")
        for e in r.events:
            f.write(line("event", e) + "\n")
        f.write(line("pre", r.pre) + "\n")
        f.write(",".join(names) + "\n")
        for i in range(len(columns[0])):
            f.write(",".join(repr(float(c[i])) if n != "segment" else str(int(c[i]))
                             for n, c in zip(names, columns)) + "\n")
    os.replace(tmp, path)


def run_simulate(kwargs):
    """mdrmap.simulate(**kwargs); UserError (one line) if it refuses or fails."""
    from .. import InvalidInput, simulate
    try:
        return simulate(**kwargs)
    except InvalidInput as e:
        raise UserError(f"mdrmap.simulate: {e}") from None
    except RuntimeError as e:
        raise UserError(f"mdrmap.simulate failed: {e}") from None


def case_kwargs(a):
    """The case of the tools' common arguments as mdrmap.simulate keywords
    (F0 or d, R, tau, G, and the spectrum with --prony)."""
    if (a.F0 is None) == (a.d is None):
        raise UserError("give exactly one of --F0 F0 (load control) or --d D (depth control)")
    for name in ("F0", "d", "R", "tau", "G"):
        x = getattr(a, name)
        if x is not None and not (math.isfinite(x) and (x > 0 or (name == "tau" and x == 0))):
            raise UserError(f"--{name}: must be a finite number > 0, got {x:g}")
    if a.tau == 0 and not a.prony:
        raise UserError("--tau: must be > 0 here without --prony (tau = 0 and no spectrum "
                        "have no transients to show)")
    out = {"F0": a.F0} if a.F0 is not None else {"d": a.d}
    out.update(R=a.R, tau=a.tau, G=a.G)
    if a.prony:
        out["prony"] = a.prony
    return out


def probe_scales(a):
    """{name: value} of the case's scales (length, depth, force, friction,
    time): Result.scales of a short mdrmap.simulate of the tools' case
    (a two-sample run)."""
    return dict(run_simulate(dict(case_kwargs(a), v=1.0, history=[(1.0, 1.0)],
                                  samples=2)).scales)


def add_common(p):
    """Options shared by the tools: the case, CSVs, figure."""
    load = p.add_mutually_exclusive_group()
    load.add_argument("--F0", type=float, help="prescribed normal load F0 (load control)")
    load.add_argument("--FN", type=float, dest="F0", help="the old spelling of --F0")
    p.add_argument("--d", type=float, help="indentation depth (depth control, instead of --F0)")
    p.add_argument("--R", type=float, default=100.0, help="indenter radius (default 100)")
    p.add_argument("--tau", type=float, default=1.0,
                   help="relaxation time (default 1; with --prony the parallel dashpot's, "
                        "0: none)")
    p.add_argument("--G", type=float, default=1.0,
                   help="shear modulus (default 1; with --prony the long-term modulus)")
    p.add_argument("--prony", metavar="G1:TAU1,G2:TAU2,...",
                   help="a relaxation spectrum, as `mdrmap simulate --prony`")
    p.add_argument("--rtol", type=float, default=1e-4, help="mdrmap's rtol (default 1e-4)")
    p.add_argument("--samples", type=int, default=121, help="samples per segment (default 121)")
    p.add_argument("--csv-dir", help="keep the runs here as CSVs in the format of "
                                     "`mdrmap simulate` (default: not kept)")
    p.add_argument("--from-csv", action="store_true",
                   help="read the runs from the CSVs in --csv-dir instead of computing them")
    p.add_argument("-o", "--output", help="write the figure to this PNG")
    p.add_argument("--dpi", type=int, default=120, help="figure resolution (default 120)")


def check_common(a):
    if a.samples < 3:
        raise UserError(f"--samples: must be an integer >= 3, got {a.samples}")
    if not (0 < a.rtol <= 0.1):
        raise UserError(f"--rtol: must be in (0, 0.1], got {a.rtol:g}")
    if a.from_csv and not a.csv_dir:
        raise UserError("--from-csv needs --csv-dir DIR (where the CSVs are)")
    if a.prony is not None:
        pairs(a.prony, "--prony")  # (the solver checks the values)
    if a.csv_dir and not a.from_csv:
        try:
            os.makedirs(a.csv_dir, exist_ok=True)
        except OSError as e:
            raise UserError(f"--csv-dir: cannot make {a.csv_dir}: {e.strerror or e}") from None
    if a.output and os.path.isdir(a.output):
        raise UserError(f"-o: {a.output} is a directory")


def obtain(a, name, kwargs, np, tool):
    """The run NAME: read from --csv-dir with --from-csv, else computed by
    mdrmap.simulate(**kwargs) (and kept in --csv-dir/NAME if given)."""
    if a.from_csv:
        run = read_csv(os.path.join(a.csv_dir, name), np)
        expect_case(run, a)
        return run
    r = run_simulate(kwargs)
    if a.csv_dir:
        write_csv(r, os.path.join(a.csv_dir, name), tool)
    return from_result(r, name)


def expect_case(run, a):
    """A CSV read with --from-csv must be the case asked for (loading, R, tau,
    G, the spectrum)."""
    want = {"R": a.R, "tau": a.tau, "G": a.G}
    want.update({"F0": a.F0} if a.F0 is not None else {"d": a.d})
    for k, v in want.items():
        got = run.case.get(k)
        if got is None or not math.isclose(got, v, rel_tol=1e-12):
            raise UserError(f"{run.path}: {k}={got} in its '# case' line, but {k}={v:g} asked "
                            f"for (rerun without --from-csv)")
    have = run.prony
    want_prony = pairs(a.prony, "--prony") if a.prony else []
    if len(have) != len(want_prony) or any(
            not math.isclose(x, y, rel_tol=1e-12)
            for p, q in zip(have, want_prony) for x, y in zip(p, q)):
        raise UserError(f"{run.path}: its spectrum (prony) is not the --prony asked for "
                        f"(rerun without --from-csv)")
