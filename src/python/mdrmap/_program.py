"""The console script `mdrmap` of a pip install: runs the program mdrmap that
the install put into the package (mdrmap/bin/mdrmap) in place of this process
(os.execv: the same process id, so `mpirun -np 4 mdrmap study ...` starts four
MPI ranks of the program itself)."""

import os
import sys


def path():
    """The bundled program: <package>/bin/mdrmap."""
    return os.path.join(os.path.dirname(os.path.abspath(__file__)), "bin", "mdrmap")


def main():
    program = path()
    if not os.access(program, os.X_OK):
        sys.exit(f"mdrmap: the program {program} is missing or not executable: reinstall "
                 "with `pip install --no-build-isolation --no-index .` from the source tree")
    os.execv(program, [program] + sys.argv[1:])
