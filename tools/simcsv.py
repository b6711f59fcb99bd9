"""Shared by the history tools (steps.py, healing.py): running `mdrmap
simulate` and reading its CSV output, with one-line errors.

Not a script: the tools import it from their own directory. Reads the format
of `mdrmap simulate --help-all` ("Output"): comment lines `# mdrmap ...`,
`# case ...`, optional `# error_vs_...`, one `# event ...` per segment,
`# pre ...`, then the header and the rows.

The scales the tools measure by (the reference length a0 or a1, depth,
force, friction a/R, time tau) are mdrmap's own: its `# scales` line (the
map's /scales). case_scales() reads them from a short probe run of the case
before the tools choose their velocities, and keeps them in the CSV
directory as scales.txt, which --from-csv reads back. Nothing here computes
a scale.
"""
import math
import os
import shutil
import subprocess

from maplib import UserError

LOAD_HEADER = "t,segment,FN,Fx,mu,a2,d,a1"  # FN: the measured normal force
DEPTH_HEADER = "t,segment,FN,Fx,mu,a2"
# the old names of case parameters -> today's: the prescribed load F0 was FN
# in the `# case` line of an earlier mdrmap (and in the tools' scales.txt)
CASE_ALIASES = {"FN": "F0"}


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
    """One simulate output: case, pre state, events, columns (numpy arrays)."""

    def __init__(self, path, case, pre, events, columns, load):
        self.path, self.case, self.pre, self.events = path, case, pre, events
        self.col, self.load = columns, load

    def scales(self):
        """(length, depth, friction) of the case: mdrmap's `# scales`
        (case_scales; a0, d0, a0/R under load, a1, d, a1/R at fixed depth)."""
        return self.sc["length"], self.sc["depth"], self.sc["friction"]

    def history(self):
        return [tuple(number(x, f"{self.path}: history") for x in seg.split(":"))
                for seg in self.case_text["history"].split(",")]

    def segment(self, k):
        """Boolean mask of segment k's rows."""
        return self.col["segment"] == k


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
    case = {k: number(v, f"{path}: {k}") for k, v in case_text.items()
            if k not in ("history", "spacing")}
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
              header == LOAD_HEADER)
    run.case_text = case_text
    return run


def find_mdrmap(given):
    """The mdrmap executable: --mdrmap, $MDRMAP, or mdrmap on PATH."""
    exe = given or os.environ.get("MDRMAP") or shutil.which("mdrmap")
    if not exe:
        raise UserError("no mdrmap executable: give --mdrmap PATH (or set MDRMAP, or put "
                        "mdrmap on PATH), or read existing CSVs with --from-csv")
    if not (os.path.isfile(exe) and os.access(exe, os.X_OK)):
        raise UserError(f"--mdrmap: not an executable file: {exe}")
    return exe


def simulate(exe, args, output):
    """Runs `mdrmap simulate ARGS --output OUTPUT`; UserError with mdrmap's own line if it fails."""
    cmd = [exe, "simulate", *args, "--output", output]
    try:
        r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    except OSError as e:
        raise UserError(f"cannot run {exe}: {e.strerror or e}") from None
    if r.returncode != 0:
        msg = (r.stderr.strip().splitlines() or ["(no message)"])[-1]
        raise UserError(f"mdrmap simulate failed (exit {r.returncode}): {msg}")


def loading_args(a):
    """The loading options of the tools' common arguments (--F0 or --d)."""
    if (a.F0 is None) == (a.d is None):
        raise UserError("give exactly one of --F0 F0 (load control) or --d D (depth control)")
    for name in ("F0", "d", "R", "tau", "G"):
        x = getattr(a, name)
        if x is not None and not (math.isfinite(x) and (x > 0 or (name == "tau" and x == 0))):
            raise UserError(f"--{name}: must be a finite number > 0, got {x:g}")
    if a.tau == 0:
        raise UserError("--tau: must be > 0 here (tau = 0 has no transients to show)")
    load = ["--F0", repr(a.F0)] if a.F0 is not None else ["--d", repr(a.d)]
    return load + ["--R", repr(a.R), "--tau", repr(a.tau), "--G", repr(a.G)]


SCALES = "scales.txt"  # the case's scales, kept in the CSV directory for --from-csv


def probe_scales(exe, a, workdir):
    """The `# scales` line of a short `mdrmap simulate` of the tools' case
    (loading, R, tau, G; a two-sample run), as {name: value}."""
    path = os.path.join(workdir, "probe.csv")
    simulate(exe, loading_args(a) + ["--v", "1", "--history", "1:1", "--samples", "2"], path)
    with open(path, encoding="utf-8") as f:
        lines = [ln for ln in f.read().splitlines() if ln.startswith("# scales ")]
    os.remove(path)
    if len(lines) != 1:
        raise UserError(f"{exe} printed no '# scales' line: an mdrmap older than these tools")
    return {k: number(v, f"probe: {k}") for k, v in fields(lines[0]).items()}


def case_scales(a, exe, workdir):
    """{name: value} of the case's scales (length, depth, force, friction,
    time): mdrmap's `# scales` line of the case (written to WORKDIR/scales.txt
    with the case), or with --from-csv read back from there; UserError if it
    is missing or is another case's."""
    path = os.path.join(workdir, SCALES)
    want = {"R": a.R, "tau": a.tau, "G": a.G}
    want.update({"F0": a.F0} if a.F0 is not None else {"d": a.d})
    if not a.from_csv:
        scales = probe_scales(exe, a, workdir)
        with open(path, "w") as f:
            f.write(" ".join(f"{k}={v!r}" for k, v in {**want, **scales}.items()) + "\n")
    if not os.path.exists(path):
        raise UserError(f"no such file: {path} (the case's scales, which a run without "
                        f"--from-csv writes there)")
    with open(path) as f:
        got = {k: number(v, f"{path}: {k}")
               for k, v in case_names(fields("# " + f.read())).items()}
    for k, v in want.items():
        if k not in got or not math.isclose(got[k], v, rel_tol=1e-12):
            raise UserError(f"{path}: {k}={got.get(k)}, but {k}={v:g} asked for (rerun without "
                            f"--from-csv)")
    return {k: v for k, v in got.items() if k not in want}


def add_common(p):
    """Options shared by the tools: the case, mdrmap, CSVs, figure."""
    load = p.add_mutually_exclusive_group()
    load.add_argument("--F0", type=float, help="prescribed normal load F0 (load control)")
    load.add_argument("--FN", type=float, dest="F0", help="the old spelling of --F0")
    p.add_argument("--d", type=float, help="indentation depth (depth control, instead of --F0)")
    p.add_argument("--R", type=float, default=100.0, help="indenter radius (default 100)")
    p.add_argument("--tau", type=float, default=1.0, help="relaxation time (default 1)")
    p.add_argument("--G", type=float, default=1.0, help="shear modulus (default 1)")
    p.add_argument("--rtol", type=float, default=1e-4, help="mdrmap --rtol (default 1e-4)")
    p.add_argument("--samples", type=int, default=121, help="samples per segment (default 121)")
    p.add_argument("--mdrmap", help="the mdrmap executable (default: $MDRMAP, then PATH)")
    p.add_argument("--csv-dir", help="keep the CSVs here (default: a temporary directory)")
    p.add_argument("--from-csv", action="store_true",
                   help="read the CSVs from --csv-dir instead of running mdrmap")
    p.add_argument("-o", "--output", help="write the figure to this PNG")
    p.add_argument("--dpi", type=int, default=120, help="figure resolution (default 120)")


def check_common(a):
    if a.samples < 3:
        raise UserError(f"--samples: must be an integer >= 3, got {a.samples}")
    if not (0 < a.rtol <= 0.1):
        raise UserError(f"--rtol: must be in (0, 0.1], got {a.rtol:g}")
    if a.from_csv and not a.csv_dir:
        raise UserError("--from-csv needs --csv-dir DIR (where the CSVs are)")
    if a.csv_dir and not a.from_csv:
        os.makedirs(a.csv_dir, exist_ok=True)
    if a.output and os.path.isdir(a.output):
        raise UserError(f"-o: {a.output} is a directory")


def obtain(a, exe, workdir, name, args, np, scales):
    """The run NAME: read from --csv-dir with --from-csv, else simulated into
    WORKDIR/NAME; `scales` (case_scales) attached."""
    path = os.path.join(workdir, name)
    if not a.from_csv:
        simulate(exe, args, path)
    run = read_csv(path, np)
    expect_case(run, a)
    run.sc = scales
    return run


def expect_case(run, a):
    """A CSV read with --from-csv must be the case asked for (loading, R, tau, G)."""
    want = {"R": a.R, "tau": a.tau, "G": a.G}
    want.update({"F0": a.F0} if a.F0 is not None else {"d": a.d})
    for k, v in want.items():
        got = run.case.get(k)
        if got is None or not math.isclose(got, v, rel_tol=1e-12):
            raise UserError(f"{run.path}: {k}={got} in its '# case' line, but {k}={v:g} asked "
                            f"for (rerun without --from-csv)")
