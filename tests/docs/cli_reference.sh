#!/usr/bin/env bash
# docs_cli_reference: the checked-in command-line reference
# (docs/reference/cli.md) is what the program generates from its option
# tables (`mdrmap help --markdown`): a changed option or help text fails this
# test until the page is regenerated.
#
#   bash tests/docs/cli_reference.sh MDRMAP SRCDIR
set -euo pipefail
mdrmap=$1 src=$2
page="$src/docs/reference/cli.md"
fresh=$(mktemp)
trap 'rm -f "$fresh"' EXIT

"$mdrmap" help --markdown >"$fresh"
if ! diff -u "$page" "$fresh" >"$fresh.diff"; then
  head -40 "$fresh.diff"
  rm -f "$fresh.diff"
  echo "docs_cli_reference: docs/reference/cli.md differs from what mdrmap generates;" \
    "regenerate it with: build/src/mdrmap help --markdown > docs/reference/cli.md"
  exit 1
fi
rm -f "$fresh.diff"
echo "docs_cli_reference: docs/reference/cli.md is what 'mdrmap help --markdown' prints"
