#!/usr/bin/env bash
# The two ways to install mdrmap, each into a fresh place under WORKDIR:
#
#   bash tests/install/test_install.sh cmake SRCDIR WORKDIR BUILD_DIR PYTHON
#   bash tests/install/test_install.sh pip   SRCDIR WORKDIR PYTHON
#
# cmake: `cmake --install BUILD_DIR --prefix WORKDIR/prefix` (a built tree),
#   then PREFIX/bin/mdrmap --version, its study and fit (--help: the programs
#   it runs, mdrmap-study and mdrmap-fit, beside it); a step run by PREFIX/bin/mdrmap and by
#   the installed package (PYTHONPATH=PREFIX/lib/python3.X/*-packages) gives
#   the same numbers bit for bit; the job scripts and tools are under
#   PREFIX/share/mdrmap, an installed map tool runs (--help) from there, and
#   the installed jobs/study.sbatch (no Slurm: mpirun -np 1, the 40 cases of
#   jobs/examples/quick.ini) finds and runs PREFIX/bin/mdrmap.
# pip: a copy of the source tree (git's tracked and untracked, not ignored
#   files; no build directories), a venv made by PYTHON with
#   --system-site-packages (numpy, setuptools, wheel from the system), and
#   `pip install --no-build-isolation --no-index COPY` (offline), then the
#   venv's console script `mdrmap` (--version, study and fit --help, the step) and its `import
#   mdrmap` (the same step, from the venv's site-packages, bit for bit).
#   CMAKE_ARGS (unless set) gets -DCMAKE_CXX_COMPILER_LAUNCHER=ccache when
#   ccache is on PATH and -DMDRMAP_WERROR=ON when CI=true (as tools/build.sh);
#   CMAKE_BUILD_PARALLEL_LEVEL defaults to 2.
# Exits 0 when every check passes, 1 naming the first that fails.
set -euo pipefail

mode=${1:?usage: test_install.sh cmake|pip SRCDIR WORKDIR ...}
SRCDIR=$(cd "${2:?SRCDIR}" && pwd)
WORKDIR=${3:?WORKDIR}
fail() {
  echo "test_install ($mode): FAIL: $*" >&2
  exit 1
}
log() { echo "test_install ($mode): $*"; }

rm -rf "$WORKDIR"
mkdir -p "$WORKDIR"
WORKDIR=$(cd "$WORKDIR" && pwd)
cd "$WORKDIR"
unset PYTHONPATH
export PYTHONDONTWRITEBYTECODE=1

# A step with a history (the MDR solver) and a few samples.
STEP=(--d 0.01 --R 1 --tau 1 --v 1 --history "0.1:1,1:1" --samples 3)

# check_step PROGRAM PYTHON: the program's CSV and the module's arrays of the
# same step are equal bit for bit (both print and carry the shortest
# round-tripping doubles).
check_step() {
  local program=$1 python=$2
  "$program" simulate "${STEP[@]}" --output "$WORKDIR/step.csv" ||
    fail "$program simulate ${STEP[*]} failed"
  "$python" - "$WORKDIR/step.csv" <<'EOF' || fail "the module's step differs from the program's"
import sys
import mdrmap
r = mdrmap.simulate(d=0.01, R=1, tau=1, v=1, history=[(0.1, 1), (1, 1)], samples=3)
with open(sys.argv[1]) as f:
    lines = [line.strip() for line in f if line.strip() and not line.startswith("#")]
header, rows = lines[0].split(","), [[float(x) for x in line.split(",")] for line in lines[1:]]
assert len(rows) == len(r.t) > 0, (len(rows), len(r.t))
for name in ("t", "FN", "Fx", "mu", "a2"):
    column = [row[header.index(name)] for row in rows]
    assert column == list(getattr(r, name)), (name, column, list(getattr(r, name)))
print(f"module {mdrmap.__file__}: {len(rows)} samples equal the program's")
EOF
}

# check_tools PYTHON: `python -m mdrmap --help` lists the tools of the installed
# package (mdrmap.tools), and one of them runs from it
check_tools() {
  local python=$1
  "$python" -m mdrmap --help >"$WORKDIR/tools.txt" || fail "$python -m mdrmap --help failed"
  for t in plot_run steps healing map_summary plot_map mapxr; do
    grep -q "^  $t " "$WORKDIR/tools.txt" || fail "$python -m mdrmap --help does not list $t"
  done
  "$python" -m mdrmap steps --help >"$WORKDIR/tool.txt" 2>&1 ||
    fail "$python -m mdrmap steps --help failed: $(tail -n 3 "$WORKDIR/tool.txt")"
  "$python" -c 'import mdrmap.tools, sys; assert mdrmap.tools.__file__.startswith(sys.argv[1]), mdrmap.tools.__file__' \
    "$(dirname "$("$python" -c 'import mdrmap; print(mdrmap.__file__)')")" ||
    fail "mdrmap.tools is not the installed package's"
}

# check_siblings PROGRAM: the programs it runs for study and fit were
# installed beside it (their help, through PROGRAM)
check_siblings() {
  local program=$1 cmd
  for cmd in study fit; do
    "$program" "$cmd" --help >"$WORKDIR/$cmd.txt" 2>&1 ||
      fail "$program $cmd --help failed: $(tail -n 2 "$WORKDIR/$cmd.txt")"
    grep -q "^Usage: .*mdrmap $cmd" "$WORKDIR/$cmd.txt" ||
      fail "$program $cmd --help printed no usage: $(head -n 2 "$WORKDIR/$cmd.txt")"
  done
}

install_cmake() {
  local build=${4:?BUILD_DIR} python=${5:?PYTHON} prefix=$WORKDIR/prefix
  log "cmake --install $build --prefix $prefix"
  cmake --install "$build" --prefix "$prefix" >"$WORKDIR/install.log" ||
    fail "cmake --install failed (see $WORKDIR/install.log)"
  [[ -x "$prefix/bin/mdrmap" ]] || fail "no $prefix/bin/mdrmap"
  "$prefix/bin/mdrmap" --version || fail "$prefix/bin/mdrmap --version failed"
  check_siblings "$prefix/bin/mdrmap"
  local init
  init=$(find "$prefix/lib" -path '*-packages/mdrmap/__init__.py' | head -n 1)
  [[ -n "$init" ]] || fail "no package mdrmap under $prefix/lib"
  export PYTHONPATH=${init%/mdrmap/__init__.py}
  check_step "$prefix/bin/mdrmap" "$python"
  local share=$prefix/share/mdrmap f
  for f in jobs/study.sbatch jobs/study.pbs jobs/lib/study_job.sh jobs/examples/quick.ini \
    tools/pyrun tools/maps/check_map.py; do
    [[ -f "$share/$f" ]] || fail "no $share/$f"
  done
  [[ -x "$share/tools/pyrun" ]] ||
    fail "the installed tools/pyrun is not executable"
  check_tools "$python"
  # the installed pyrun runs the installed package's tools
  bash "$share/tools/pyrun" -m mdrmap map_summary --help >"$WORKDIR/tool.txt" ||
    fail "the installed tools/pyrun -m mdrmap map_summary --help failed"
  grep -q "^usage: python -m mdrmap map_summary" "$WORKDIR/tool.txt" ||
    fail "the installed pyrun's map_summary printed no usage"
  # the installed job script, run outside a checkout, runs PREFIX/bin/mdrmap
  if [[ "$(id -u)" == 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
  CONFIG=$share/jobs/examples/quick.ini OUTPUT=$WORKDIR/quick.h5 NP=1 MDRMAP='' \
    bash "$share/jobs/study.sbatch" >"$WORKDIR/job.log" 2>&1 ||
    fail "the installed jobs/study.sbatch failed (see $WORKDIR/job.log)"
  grep -q "running: .* $share/jobs/lib/../../../../bin/mdrmap study" "$WORKDIR/job.log" ||
    fail "the installed jobs/study.sbatch did not run $prefix/bin/mdrmap (see $WORKDIR/job.log)"
  grep -q "the map is complete" "$WORKDIR/job.log" ||
    fail "the installed jobs/study.sbatch did not complete the map (see $WORKDIR/job.log)"
  log "ok"
}

# copy_source SRC DEST: what a clone with the local edits has, no builds.
copy_source() {
  local src=$1 dest=$2
  mkdir -p "$dest"
  if git -C "$src" rev-parse --show-toplevel >/dev/null 2>&1; then
    (cd "$src" && git ls-files -z -c -o --exclude-standard |
      tar --null -T - --ignore-failed-read -cf - 2>/dev/null) | tar -C "$dest" -xf -
  else
    tar -C "$src" --exclude='./build*' --exclude=./out --exclude='*.egg-info' -cf - . |
      tar -C "$dest" -xf -
  fi
  [[ -f "$dest/pyproject.toml" && -f "$dest/CMakeLists.txt" ]] ||
    fail "the copy of $src in $dest lacks pyproject.toml or CMakeLists.txt"
}

install_pip() {
  local python=${4:?PYTHON} venv=$WORKDIR/venv src=$WORKDIR/src
  copy_source "$SRCDIR" "$src"
  "$python" -m venv --system-site-packages "$venv" || fail "$python -m venv failed"
  if [[ -z "${CMAKE_ARGS:-}" ]]; then
    CMAKE_ARGS=""
    command -v ccache >/dev/null && CMAKE_ARGS="-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"
    [[ "${CI:-}" == true ]] && CMAKE_ARGS+=" -DMDRMAP_WERROR=ON" # as tools/build.sh
    export CMAKE_ARGS
  fi
  export CMAKE_BUILD_PARALLEL_LEVEL=${CMAKE_BUILD_PARALLEL_LEVEL:-2}
  local pip=("$venv/bin/python" -m pip install -v --no-cache-dir --no-build-isolation --no-index)
  log "${pip[*]} $src (CMAKE_ARGS=$CMAKE_ARGS)"
  "${pip[@]}" "$src" >"$WORKDIR/pip.log" 2>&1 || {
    tail -n 40 "$WORKDIR/pip.log" >&2
    fail "pip install failed (see $WORKDIR/pip.log)"
  }
  [[ -x "$venv/bin/mdrmap" ]] || fail "pip installed no console script $venv/bin/mdrmap"
  "$venv/bin/mdrmap" --version || fail "the console script mdrmap --version failed"
  check_siblings "$venv/bin/mdrmap"
  "$venv/bin/python" -c \
    'import mdrmap, sys; assert mdrmap.__file__.startswith(sys.prefix), mdrmap.__file__' ||
    fail "import mdrmap in the venv does not load the installed package"
  check_step "$venv/bin/mdrmap" "$venv/bin/python"
  check_tools "$venv/bin/python"
  log "ok"
}

case $mode in
cmake) install_cmake "$@" ;;
pip) install_pip "$@" ;;
*) fail "unknown mode $mode (cmake or pip)" ;;
esac
