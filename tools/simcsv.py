"""Shared by the history tools (steps.py, healing.py): running `mdrmap
simulate` and reading its CSV output, with one-line errors.

Not a script: the tools import it from their own directory. Reads the format
of `mdrmap simulate --help` ("Output"): comment lines `# mdrmap ...`,
`# case ...`, optional `# error_vs_...`, one `# event ...` per segment,
`# pre ...`, then the header and the rows.
"""
import math
import os
import shutil
import subprocess

from maplib import UserError

LOAD_HEADER = "t,segment,FN,Fx,mu,a2,d,a1"
DEPTH_HEADER = "t,segment,FN,Fx,mu,a2"


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
        """(a, d_ref, mu_ref): a0, d0 = a0^2/R, a0/R under load; a1, d, sqrt(d/R) at fixed depth."""
        R = self.case["R"]
        a = self.case["a0"] if self.load else math.sqrt(R * self.case["d"])
        return a, a * a / R, a / R

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
    case_text = fields(case_lines[0])
    case = {k: number(v, f"{path}: {k}") for k, v in case_text.items()
            if k not in ("history", "spacing")}
    pre = {k: number(v, f"{path}: pre {k}") for k, v in fields(pre_lines[0]).items()}
    events = [{k: number(v, f"{path}: event {k}") for k, v in fields(ln).items()}
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
    """The loading options of the tools' common arguments (--FN or --d)."""
    if (a.FN is None) == (a.d is None):
        raise UserError("give exactly one of --FN F0 (load control) or --d D (depth control)")
    for name in ("FN", "d", "R", "tau", "G"):
        x = getattr(a, name)
        if x is not None and not (math.isfinite(x) and (x > 0 or (name == "tau" and x == 0))):
            raise UserError(f"--{name}: must be a finite number > 0, got {x:g}")
    if a.tau == 0:
        raise UserError("--tau: must be > 0 here (tau = 0 has no transients to show)")
    load = ["--FN", repr(a.FN)] if a.FN is not None else ["--d", repr(a.d)]
    return load + ["--R", repr(a.R), "--tau", repr(a.tau), "--G", repr(a.G)]


def length_scale(a):
    """a0 (Hertz radius of F0) under load, a1 = sqrt(R d) at fixed depth."""
    if a.FN is not None:
        return (3.0 * a.FN * a.R / (16.0 * a.G)) ** (1.0 / 3.0)
    return math.sqrt(a.R * a.d)


def add_common(p):
    """Options shared by the tools: the case, mdrmap, CSVs, figure."""
    p.add_argument("--FN", type=float, help="prescribed normal force F0 (load control)")
    p.add_argument("--d", type=float, help="indentation depth (depth control, instead of --FN)")
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


def obtain(a, exe, workdir, name, args, np):
    """The run NAME: read from --csv-dir with --from-csv, else simulated into WORKDIR/NAME."""
    path = os.path.join(workdir, name)
    if not a.from_csv:
        simulate(exe, args, path)
    run = read_csv(path, np)
    expect_case(run, a)
    return run


def expect_case(run, a):
    """A CSV read with --from-csv must be the case asked for (loading, R, tau, G)."""
    want = {"R": a.R, "tau": a.tau, "G": a.G}
    want.update({"FN": a.FN} if a.FN is not None else {"d": a.d})
    for k, v in want.items():
        got = run.case.get(k)
        if got is None or not math.isclose(got, v, rel_tol=1e-12):
            raise UserError(f"{run.path}: {k}={got} in its '# case' line, but {k}={v:g} asked "
                            f"for (rerun without --from-csv)")
