"""pytest setup of the Python module's tests (CTest runs them, label python).

Environment (tests/CMakeLists.txt sets it): PYTHONPATH=<build>/python (the
package mdrmap), MDRMAP_EXE (the mdrmap binary the results are compared
with), MDRMAP_SRCDIR (the source tree: tests/test_cli.cpp, tools/,
jobs/examples/).
"""
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
