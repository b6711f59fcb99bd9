#!/usr/bin/env python3
"""The floors of src/core (docs/design/code.md, "Architecture"): each file
includes only the core's headers of its own floor and the floors below,
model < numerics < metrics < solvers < outputs, and nothing of the layers above the core
(case, study, io, app, material, fit, python).

    python3 tests/structure/core_floors.py SOURCE_DIR

Prints one line per offending include and exits 1; exits 0 when there is
none. (tests/structure/model_alone.cpp makes the model's floor a link check
too.)
"""
import pathlib
import re
import sys

FLOORS = ["model", "numerics", "metrics", "solvers", "outputs"]
INCLUDE = re.compile(r'^[ \t]*#[ \t]*include[ \t]*"([^"]+)"', re.M)


def floor_of(path):
    """The floor of a path under core/ ('core/metrics/x.hpp' -> 1), None outside."""
    parts = pathlib.PurePosixPath(path).parts
    if len(parts) >= 2 and parts[0] == "core" and parts[1] in FLOORS:
        return FLOORS.index(parts[1])
    return None


def offences(src):
    """(file, line, include, why) of every include that breaks the floors."""
    core = src / "core"
    out = []
    for f in sorted(core.rglob("*")):
        if f.suffix not in (".hpp", ".cpp"):
            continue
        rel = f.relative_to(src).as_posix()
        own = floor_of(rel)
        if own is None:
            out.append((rel, 0, "", "is in no floor of " + ", ".join(FLOORS)))
            continue
        text = f.read_text()
        for m in INCLUDE.finditer(text):
            inc = m.group(1)
            line = text.count("\n", 0, m.start()) + 1
            theirs = floor_of(inc)
            if theirs is None:
                if (src / inc).exists() or "/" in inc:
                    out.append((rel, line, inc, "is outside the core's floors"))
            elif theirs > own:
                out.append((rel, line, inc, f"is of the floor {FLOORS[theirs]}, "
                                            f"above {FLOORS[own]}"))
    return out


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: core_floors.py SOURCE_DIR (the repository's src/)")
    src = pathlib.Path(sys.argv[1])
    if not (src / "core" / "model").is_dir():
        sys.exit(f"core_floors.py: {src} has no core/model")
    bad = offences(src)
    for rel, line, inc, why in bad:
        print(f'src/{rel}:{line}: #include "{inc}" {why}')
    n = sum(1 for _ in (src / "core").rglob("*.?pp"))
    print(f"core_floors: {n} files, {len(bad)} includes across the floors")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
