"""python -m mdrmap TOOL [ARGS...]: runs a post-processing tool of the package
(mdrmap.tools); `python -m mdrmap --help` lists them, `python -m mdrmap TOOL
--help` explains one. The computations themselves are the program's
(`mdrmap simulate`, `mdrmap study`, ...) and mdrmap.simulate's."""

import sys

from . import __version__
from .tools import TOOLS, run, tool_name

PROG = "python -m mdrmap"


def usage():
    width = max(len(n) for n in TOOLS)
    lines = [f"usage: {PROG} TOOL [ARGS...]   ({PROG} TOOL --help: the tool's options)",
             "", "The post-processing tools of mdrmap " + __version__ + ":", ""]
    lines += [f"  {name:<{width}}  {what}" for name, what in TOOLS.items()]
    lines += ["", "The computations are the program's: mdrmap simulate, mdrmap study, ... "
              "(mdrmap --help), and mdrmap.simulate in Python."]
    return "\n".join(lines)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    if not argv:
        print(f"{PROG}: give a tool: {', '.join(TOOLS)} (see --help)", file=sys.stderr)
        return 2
    if argv[0] in ("-h", "--help", "help"):
        print(usage())
        return 0
    if argv[0] == "--version":
        print("mdrmap " + __version__)
        return 0
    name = tool_name(argv[0])
    if name is None:
        print(f"{PROG}: no tool {argv[0]!r} (tools: {', '.join(TOOLS)}; the program's "
              "subcommands simulate, study, ... are the command mdrmap's)", file=sys.stderr)
        return 2
    sys.argv[0] = f"{PROG} {name}"
    try:
        return run(name, argv[1:])
    except ModuleNotFoundError as e:
        if e.name is None or e.name.split(".")[0] == "mdrmap":
            raise
        top = e.name.split(".")[0]
        print(f"{PROG} {name}: needs the Python module {top}, which this Python "
              f"({sys.executable}) cannot import: pip install {top} (Debian: apt-get install "
              f"python3-{top})", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
