#!/usr/bin/env bash
# A generated reference page's drift test (docs_config_reference,
# docs_map_reference, docs_python_reference): the checked-in page PAGE
# (relative to SRCDIR) is what COMMAND... prints; a changed table or
# docstring fails the test until the pages are regenerated.
#
#   bash tests/docs/reference_page.sh NAME SRCDIR PAGE COMMAND...
set -euo pipefail
name=$1 src=$2 page=$3
shift 3
fresh=$(mktemp)
trap 'rm -f "$fresh" "$fresh.diff"' EXIT

"$@" >"$fresh"
if ! diff -u "$src/$page" "$fresh" >"$fresh.diff"; then
  head -40 "$fresh.diff"
  echo "$name: $page differs from what its generator prints; regenerate the reference" \
    "pages with: cmake --build build --target reference_docs"
  exit 1
fi
echo "$name: $page is what its generator prints"
