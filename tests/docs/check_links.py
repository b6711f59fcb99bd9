#!/usr/bin/env python3
"""docs_links: every internal link of the user guide resolves.

    check_links.py SRCDIR            # README.md, docs/*.md and jobs/README.md
    check_links.py --self-test       # the checker finds a broken link and anchor

A link or image `[text](target)` outside code whose target has no URL scheme
must name an existing file or directory, relative to the page; a `#anchor`
must be a heading of the target page (or of the page itself), slugged as
GitHub and MyST (myst_heading_anchors) make them: lower case, punctuation
other than '-' and '_' dropped, spaces as '-', a repeated slug numbered -1,
-2, ... A page that includes another with MyST's {include} directive also has
that page's headings. Prints one line per broken link; exit 1 if any.
"""
import os
import re
import sys
import tempfile

FENCE = re.compile(r"^\s*(```|~~~)")
LINK = re.compile(r"!?\[((?:[^\[\]]|\[[^\]]*\])*)\]\(\s*<?([^)\s>]*)>?(?:\s+\"[^\"]*\")?\s*\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
INCLUDE = re.compile(r"^\s*```\{include\}\s+(\S+)")


def prose_lines(text):
    """(line number, line) of the lines outside fenced code, inline code removed."""
    fence = None
    for n, line in enumerate(text.split("\n"), 1):
        m = FENCE.match(line)
        if m:
            if fence is None:
                fence = m.group(1)
            elif m.group(1) == fence:
                fence = None
            continue
        if fence is None:
            yield n, re.sub(r"`[^`]*`", "", line)


def slug(title):
    title = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", title)  # a link's text
    title = title.replace("`", "")
    return re.sub(r"[^\w\- ]", "", title.strip().lower()).replace(" ", "-")


def anchors(path, seen=None):
    """The heading anchors of a Markdown page, with those of the pages it includes."""
    seen = seen or set()
    if path in seen or not os.path.isfile(path):
        return set()
    seen.add(path)
    with open(path, encoding="utf-8") as f:
        text = f.read()
    result, counts = set(), {}
    fence = None
    for line in text.split("\n"):
        inc = INCLUDE.match(line)
        if inc and fence is None:
            result |= anchors(os.path.normpath(os.path.join(os.path.dirname(path), inc.group(1))), seen)
        m = FENCE.match(line)
        if m:
            fence = m.group(1) if fence is None else (None if m.group(1) == fence else fence)
            continue
        h = HEADING.match(line) if fence is None else None
        if h:
            s = slug(h.group(2))
            k = counts.get(s, 0)
            counts[s] = k + 1
            result.add(s if k == 0 else f"{s}-{k}")
    return result


def broken_links(page):
    with open(page, encoding="utf-8") as f:
        text = f.read()
    for n, line in prose_lines(text):
        for m in LINK.finditer(line):
            target = m.group(2)
            if not target or re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target):
                continue  # external (http:, mailto:, ...)
            path, _, anchor = target.partition("#")
            dest = os.path.normpath(os.path.join(os.path.dirname(page), path)) if path else page
            if not os.path.exists(dest):
                yield f"{page}:{n}: link to a missing file: {target}"
            elif anchor and not dest.endswith(".md"):
                yield f"{page}:{n}: an anchor into a file that is not Markdown: {target}"
            elif anchor and anchor not in anchors(dest):
                yield f"{page}:{n}: no heading for the anchor #{anchor} in {dest}: {target}"


def pages(srcdir):
    docs = os.path.join(srcdir, "docs")
    found = [os.path.join(srcdir, "README.md"), os.path.join(srcdir, "jobs", "README.md")]
    found += sorted(os.path.join(docs, p) for p in os.listdir(docs) if p.endswith(".md"))
    design = os.path.join(docs, "design")  # the design notes' pages
    if os.path.isdir(design):
        found += sorted(os.path.join(design, p) for p in os.listdir(design) if p.endswith(".md"))
    return [p for p in found if os.path.isfile(p)]


def self_test():
    with tempfile.TemporaryDirectory() as d:
        os.mkdir(os.path.join(d, "docs"))
        with open(os.path.join(d, "README.md"), "w") as f:
            f.write("# T\n\n[ok](docs/a.md#the-a-section) [ok](#t) `[code](nope.md)`\n"
                    "```sh\n[fenced](nope.md)\n```\n"
                    "[gone](docs/missing.md) [bad](docs/a.md#nowhere) ![img](docs/x.png)\n")
        with open(os.path.join(d, "docs", "a.md"), "w") as f:
            f.write("# A\n\n## The `a` section\n\n[inc](b.md#from-b) [dup](#a-1)\n\n"
                    "```{include} ../inc.md\n```\n\n## A\n")
        with open(os.path.join(d, "docs", "b.md"), "w") as f:
            f.write("```{include} ../inc.md\n```\n")
        with open(os.path.join(d, "inc.md"), "w") as f:
            f.write("## From B\n")
        found = [line for p in pages(d) for line in broken_links(p)]
        want = ["missing.md", "#nowhere", "x.png"]
        ok = len(found) == len(want) and all(any(w in line for line in found) for w in want)
        print("self-test:", "passed" if ok else "FAILED", *found, sep="\n  ")
        return ok


def main(argv):
    if argv[1:] == ["--self-test"]:
        return 0 if self_test() else 1
    if len(argv) != 2:
        print(__doc__.strip().split("\n\n")[1], file=sys.stderr)
        return 2
    if not self_test():
        return 1
    checked = pages(argv[1])
    bad = [line for p in checked for line in broken_links(p)]
    for line in bad:
        print(line)
    print(f"docs_links: {len(checked)} pages, {len(bad)} broken links")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
