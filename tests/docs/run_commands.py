#!/usr/bin/env python3
"""docs_commands: the single-case commands of the guide run as written.

    run_commands.py MDRMAP SRCDIR

Every `mdrmap simulate`, `mdrmap stationary` or `mdrmap fit` command (also spelled
`build/src/mdrmap ...`) in a ```sh block of README.md and docs/*.md, with its
backslash continuations, runs with the built MDRMAP in a scratch directory
that links the repository's jobs/ (the example files the commands name). Each
must exit 0, and write a non-empty file where it names an --output. A self-test
first checks that a command with a bad option is reported. Exit 1 if any fails.
"""
import os
import re
import shlex
import subprocess
import sys
import tempfile

BLOCK = re.compile(r"^```(?:sh|bash|console)\n(.*?)^```", re.S | re.M)
COMMAND = re.compile(r"^(?:build/src/)?mdrmap (simulate|stationary|fit)\b")


def commands(page):
    """(line number, argv) of the single-case commands in a page's shell blocks."""
    with open(page, encoding="utf-8") as f:
        text = f.read()
    for block in BLOCK.finditer(text):
        first = text.count("\n", 0, block.start(1)) + 1
        lines = block.group(1).split("\n")
        i = 0
        while i < len(lines):
            start, line = i, lines[i].strip()
            while line.endswith("\\") and i + 1 < len(lines):
                i += 1
                line = line[:-1] + " " + lines[i].strip()
            i += 1
            if COMMAND.match(line):
                argv = shlex.split(line, comments=True)
                yield first + start, argv[1:]


def run(exe, srcdir, page, line, args, work):
    p = subprocess.run([exe] + args, cwd=work, capture_output=True, text=True, timeout=60)
    where = f"{os.path.relpath(page, srcdir)}:{line}: mdrmap {' '.join(args)}"
    if p.returncode != 0:
        return f"{where}\n  exit {p.returncode}: {p.stderr.strip()}"
    if "--output" in args:
        out = os.path.join(work, args[args.index("--output") + 1])
        if not os.path.isfile(out) or os.path.getsize(out) == 0:
            return f"{where}\n  wrote no {out}"
    return None


def check(exe, srcdir, pages):
    failures, count = [], 0
    with tempfile.TemporaryDirectory() as work:
        os.symlink(os.path.join(srcdir, "jobs"), os.path.join(work, "jobs"))
        for page in pages:
            for line, args in commands(page):
                count += 1
                problem = run(exe, srcdir, page, line, args, work)
                if problem:
                    failures.append(problem)
    return count, failures


def self_test(exe, srcdir):
    with tempfile.TemporaryDirectory() as d:
        page = os.path.join(d, "page.md")
        with open(page, "w") as f:
            f.write("```sh\nmdrmap simulate --d 0.1 --R 10 --tau 1 --v 2 \\\n"
                    "    --v1 0.5 --output a.csv   # fine\n"
                    "build/src/mdrmap stationary --d 0.1 --R 10 --tau 1 --v 2 --no-such-option 1\n```\n")
        count, failures = check(exe, srcdir, [page])
        ok = count == 2 and len(failures) == 1 and "no-such-option" in failures[0]
        print("self-test:", "passed" if ok else f"FAILED ({count} commands, {failures})")
        return ok


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip().split("\n\n")[1], file=sys.stderr)
        return 2
    exe, srcdir = os.path.abspath(argv[1]), os.path.abspath(argv[2])
    if not self_test(exe, srcdir):
        return 1
    docs = os.path.join(srcdir, "docs")
    pages = [os.path.join(srcdir, "README.md")]
    pages += sorted(os.path.join(docs, p) for p in os.listdir(docs) if p.endswith(".md"))
    count, failures = check(exe, srcdir, pages)
    for problem in failures:
        print(problem)
    print(f"docs_commands: {count} commands, {len(failures)} failed")
    return 1 if failures or count == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
