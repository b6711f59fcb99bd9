"""The two examples of docs/examples run as a user runs them: the fit recovers
tau and d within their confidence intervals; the healing table through the
module equals the tool's (python -m mdrmap healing, which computes its runs with
mdrmap.simulate itself)."""
import os
import subprocess
import sys


def run(args, env=None):
    p = subprocess.run(args, capture_output=True, text=True, timeout=300, env=env)
    assert p.returncode == 0, p.stdout + p.stderr
    return p.stdout


def test_fit_recovers_tau_and_d(srcdir):
    out = run([sys.executable, f"{srcdir}/docs/examples/fit_tau_d.py"])
    print(out)
    assert "recovered the true values" in out
    assert out.count("inside") == 2 and "run time" in out


def test_healing_through_the_module_equals_the_tool(srcdir, exe):
    mine = run([sys.executable, f"{srcdir}/docs/examples/healing.py"])
    theirs = run([sys.executable, "-m", "mdrmap", "healing", "--F0", "0.0533",
                  "--holds", "0.1,1,10,100"], env=dict(os.environ))
    assert mine == theirs
    assert "slope" in mine and len(mine.splitlines()) == 8
