#!/usr/bin/env bash
# Regenerates the generated reference pages of the guide (docs/reference/)
# from a build: cli.md, config.md and map-schema.md from the program's tables
# (mdrmap help --markdown [PAGE]), python.md from the built module's
# docstrings (tests/docs/python_reference.py; skipped with a note when the
# module is not built). The tests docs_*_reference fail until they are.
#
#   bash tools/reference_docs.sh [BUILD_DIR [PYTHON]]    (default: build, /usr/bin/python3)
#   cmake --build build --target reference_docs         (the same, after building both)
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$(cd "${1:-$ROOT/build}" && pwd)
python=${2:-/usr/bin/python3}
mdrmap="$build/src/mdrmap"
pages="$ROOT/docs/reference"

# write each page whole or not at all (a failed generator leaves the old page)
write() {
  local page=$1
  shift
  "$@" >"$pages/$page.tmp" || { rm -f "$pages/$page.tmp"; return 1; }
  mv "$pages/$page.tmp" "$pages/$page"
  echo "reference_docs: wrote docs/reference/$page"
}

write cli.md "$mdrmap" help --markdown
write config.md "$mdrmap" help --markdown config
write map-schema.md "$mdrmap" help --markdown map-schema
if [[ -d "$build/python/mdrmap" ]] && ls "$build"/python/mdrmap/_core*.so >/dev/null 2>&1; then
  write python.md env PYTHONPATH="$build/python" PYTHONDONTWRITEBYTECODE=1 \
    "$python" "$ROOT/tests/docs/python_reference.py"
else
  echo "reference_docs: docs/reference/python.md not regenerated: the module is not built" \
    "in $build/python (cmake --build $build --target mdrmap_python)" >&2
fi
