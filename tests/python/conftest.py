"""pytest setup of the Python module's tests (CTest runs them, label python).

Environment (tests/CMakeLists.txt sets it): PYTHONPATH=<build>/python (the
package mdrmap), MDRMAP_EXE (the mdrmap binary the results are compared
with), MDRMAP_CASE_SET_EXE (prints the C++ tests' case sets), MDRMAP_SRCDIR (the source tree: tests/test_cli.cpp, tools/,
jobs/examples/).
"""
import json
import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def exe():
    return os.environ["MDRMAP_EXE"]


@pytest.fixture(scope="session")
def srcdir():
    return os.environ["MDRMAP_SRCDIR"]


def run_cli(exe, args):
    """`mdrmap simulate ARGS`: (exit code, stdout, stderr)."""
    p = subprocess.run([exe, "simulate"] + list(args), capture_output=True, text=True,
                       timeout=300)
    return p.returncode, p.stdout, p.stderr


def case_set(which, samples):
    """The C++ tests' case set `which` ("history" or "load", tests/cases) at
    `samples` per segment: [(name, keyword arguments of mdrmap.simulate)]."""
    p = subprocess.run([os.environ["MDRMAP_CASE_SET_EXE"], which, str(samples)],
                       capture_output=True, text=True, timeout=60, check=True)
    out = []
    for line in p.stdout.splitlines():
        rec = json.loads(line)
        kw = rec["kw"]
        kw["history"] = [tuple(seg) for seg in kw["history"]]
        out.append((rec["name"], kw))
    return out
