#!/usr/bin/env bash
# docs_readme_length: README.md stays a front page of at most 250 lines (what
# mdrmap is, install, the quick start, recipes, links); the detail belongs in
# the user guide under docs/.
#
#   bash tests/docs/readme_length.sh SRCDIR
set -euo pipefail
max=250
n=$(wc -l <"$1/README.md")
if ((n > max)); then
  echo "docs_readme_length: README.md has $n lines, at most $max: move the detail into docs/"
  exit 1
fi
echo "docs_readme_length: README.md has $n lines (at most $max)"
