#!/usr/bin/env bash
# docs_site: builds the user guide (docs/, Sphinx with MyST Markdown and the
# furo theme) as HTML with warnings as errors: a broken cross-reference or
# anchor, a page outside the table of contents, bad MyST syntax all fail.
#
#   bash tests/docs/site.sh SRCDIR OUTDIR
#
# Exit 77 (skipped) when no Python has sphinx, myst_parser and furo (Debian:
# python3-sphinx python3-myst-parser furo; tools/setup.sh installs them).
set -euo pipefail
src=$1 out=$2

py=""
for cand in ${PYTHON:-} /usr/bin/python3 python3; do
  if command -v "$cand" >/dev/null 2>&1 &&
    "$cand" -c "import sphinx, myst_parser, furo" >/dev/null 2>&1; then
    py=$cand
    break
  fi
done
if [[ -z "$py" ]]; then
  echo "docs_site: skipped: no Python with sphinx, myst_parser and furo" \
    "(Debian: python3-sphinx python3-myst-parser furo; bash tools/setup.sh)"
  exit 77
fi

rm -rf "$out"
"$py" -m sphinx -W --keep-going -E -q -b html -d "$out/.doctrees" "$src/docs" "$out"
for page in index install quickstart studies python physics changelog design reference/config reference/map-schema reference/python jobs; do
  [[ -s "$out/$page.html" ]] || { echo "docs_site: $out/$page.html was not written"; exit 1; }
done
echo "docs_site: built $(find "$out" -maxdepth 1 -name '*.html' | wc -l) pages in $out"
