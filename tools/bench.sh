#!/usr/bin/env bash
# The work-precision benchmark of the solvers (issue 3), in one command:
#
#   bash tools/bench.sh [--quick] [--no-profile] [--publish]
#
#   1. installs missing Debian packages (tools/setup.sh) and builds mdrmap_bench
#      in Release (tools/build.sh, build directory $BUILD_DIR);
#   2. records the machine in $OUT_DIR/machine.txt (lscpu model name, cores,
#      memory, OS, compiler, date, git commit);
#   3. runs mdrmap_bench, which writes $OUT_DIR/bench.csv (one row per setting
#      and case subset), bench_cases.csv (one row per setting and scene) and
#      bench.md (machine, tables, the cost targets, peak memory);
#   3b. runs mdrmap_bench_history (velocity histories: history.csv, history.md)
#       and mdrmap_bench_load (load control against the fixed-step load
#       baseline, issue 11: load.csv, load.md) and mdrmap_bench_material (an
#       11-term elastomer and the 30-term PIB spectrum over a lab velocity-step
#       test, and the growth with 10x longer segments: material.csv,
#       material.md); all appended to bench.md;
#   3d. the seed's own workload against the build before velocity histories
#       (issue 22, tools/bench/seed_ratio.sh): CPU of the 1e5-case one-step
#       grid, this build's mdrmap against commit 8876e42 built in a scratch
#       directory, 5 alternating pairs, the median ratio in seed_ratio.txt
#       and bench.md (target <= 1.00; skipped with --quick);
#   4. plots $OUT_DIR/work_precision.png and load_work_precision.png
#      (tools/pyrun tools/plot_bench.py);
#   5. profiles with valgrind --tool=callgrind (skipped with --no-profile or
#      --quick, or when valgrind is not installed): mdrmap_bench --profile row
#      and --profile auto, top functions in $OUT_DIR/profile_{row,auto}.txt.
#
# --quick      smoke run of a few seconds (short ladders, one call per scene)
# --no-profile skip step 5
# --publish    copy bench.md, bench.csv, history.csv, load.csv, work_precision.png
#              and load_work_precision.png to tools/bench/, where docs/performance.md
#              takes them from
#
# Environment: BUILD_DIR=build-bench, OUT_DIR=out/bench (relative to the
# repository root, or absolute), JOBS, CI (as tools/build.sh), SCRATCH (where
# step 3d builds 8876e42; default a temporary directory).
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"

quick=0 profile=1 publish=0
for arg in "$@"; do
  case "$arg" in
  --quick) quick=1 ;;
  --no-profile) profile=0 ;;
  --publish) publish=1 ;;
  -h | --help)
    sed -n '2,35p' "$0" | sed 's/^# \{0,1\}//'
    exit 0
    ;;
  *)
    echo "bench: unknown option '$arg' (see bash tools/bench.sh --help)" >&2
    exit 2
    ;;
  esac
done
((quick)) && profile=0

BUILD_DIR=${BUILD_DIR:-build-bench}
OUT_DIR=${OUT_DIR:-out/bench}
log() { printf 'bench: %s\n' "$*" >&2; }
# section TITLE FILE: appends "## TITLE" and FILE's text to bench.md
section() {
  {
    echo
    echo "## $1"
    echo
    cat "$2"
  } >>"$OUT_DIR/bench.md"
}

# 1. build (Release: timings of an unoptimised build mean nothing)
bash tools/setup.sh
BUILD_DIR="$BUILD_DIR" BUILD_TYPE=Release \
  BUILD_TARGETS="mdrmap mdrmap_bench mdrmap_bench_history mdrmap_bench_load mdrmap_bench_material" \
  bash tools/build.sh -DMDRMAP_BUILD_BENCH=ON
BENCH="$BUILD_DIR/tools/bench/mdrmap_bench"
[[ -x "$BENCH" ]] || {
  log "$BENCH was not built"
  exit 1
}
mkdir -p "$OUT_DIR"

# 2. the machine
cxx=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "$BUILD_DIR/CMakeCache.txt" | sed -n 1p)
flags=$(sed -n 's/^CMAKE_CXX_FLAGS_RELEASE:[A-Z]*=//p' "$BUILD_DIR/CMakeCache.txt" | sed -n 1p)
commit=$(git rev-parse --short=12 HEAD 2>/dev/null || echo unknown)
if [[ "$commit" != unknown ]] && ! git diff --quiet HEAD -- src tools 2>/dev/null; then
  commit="$commit (with uncommitted changes in src/ or tools/)"
fi
{
  echo "CPU:       $(lscpu | sed -n 's/^Model name:[[:space:]]*//p' | sed -n 1p)"
  echo "Cores:     $(nproc) ($(lscpu | sed -n 's/^Core(s) per socket:[[:space:]]*//p' | sed -n 1p) per socket, $(lscpu | sed -n 's/^Thread(s) per core:[[:space:]]*//p' | sed -n 1p) thread(s) per core)"
  echo "Memory:    $(free -h | awk '/^Mem:/ {print $2}')"
  echo "OS:        $(. /etc/os-release 2>/dev/null && echo "$PRETTY_NAME"), Linux $(uname -r)"
  echo "Compiler:  $("${cxx:-c++}" --version | sed -n 1p), flags $flags"
  echo "Commit:    $commit"
  echo "Date:      $(date -u '+%Y-%m-%d %H:%M UTC')"
} >"$OUT_DIR/machine.txt"
cat "$OUT_DIR/machine.txt" >&2

# 3. the benchmark
cmd="bash tools/bench.sh"
bench_args=(--out-dir "$OUT_DIR" --machine-file "$OUT_DIR/machine.txt")
if ((quick)); then
  bench_args+=(--quick)
  cmd+=" --quick"
fi
log "$BENCH ${bench_args[*]}"
"$BENCH" "${bench_args[@]}" --command "$cmd" >"$OUT_DIR/bench.log"

# 3b. velocity histories: history.csv, history.md (appended to bench.md)
HIST="$BUILD_DIR/tools/bench/mdrmap_bench_history"
hist_args=(--out "$OUT_DIR")
((quick)) && hist_args+=(--quick)
log "$HIST ${hist_args[*]}"
"$HIST" "${hist_args[@]}" >"$OUT_DIR/history.log"
section "Velocity histories ($cmd, mdrmap_bench_history)" "$OUT_DIR/history.md"

# 3c. load control: load.csv, load.md (a section of its own, appended to bench.md)
LOAD="$BUILD_DIR/tools/bench/mdrmap_bench_load"
load_args=(--out "$OUT_DIR" --command "$cmd")
((quick)) && load_args+=(--quick)
log "$LOAD ${load_args[*]}"
"$LOAD" "${load_args[@]}" >"$OUT_DIR/load.log" 2>"$OUT_DIR/load_progress.log"
{
  echo
  cat "$OUT_DIR/load.md"
} >>"$OUT_DIR/bench.md"

# 3c'. real materials over a lab test, and the growth with the segments' length
MAT="$BUILD_DIR/tools/bench/mdrmap_bench_material"
mat_args=(--out "$OUT_DIR")
((quick)) && mat_args+=(--quick)
log "$MAT ${mat_args[*]}"
"$MAT" "${mat_args[@]}" >"$OUT_DIR/material.log"
section "Real materials over a lab test ($cmd, mdrmap_bench_material)" "$OUT_DIR/material.md"

# 3d. the seed path against 8876e42 (SCRATCH: where to build it, kept if given)
if ((!quick)); then
  log "bash tools/bench/seed_ratio.sh $BUILD_DIR/src/mdrmap 5"
  bash tools/bench/seed_ratio.sh "$BUILD_DIR/src/mdrmap" 5 >"$OUT_DIR/seed_ratio.txt"
  {
    echo
    echo "## The seed's one-step grid against 8876e42 ($cmd, tools/bench/seed_ratio.sh)"
    echo
    echo '```'
    cat "$OUT_DIR/seed_ratio.txt"
    echo '```'
  } >>"$OUT_DIR/bench.md"
fi

# 4. the plot
cpu=$(lscpu | sed -n 's/^Model name:[[:space:]]*//p' | sed -n 1p)
tools/pyrun tools/plot_bench.py "$OUT_DIR/bench.csv" -o "$OUT_DIR/work_precision.png" \
  --title "$cpu, $(nproc) cores, $(date -u '+%Y-%m-%d')$( ((quick)) && echo ' (--quick smoke run)')"
tools/pyrun tools/plot_bench.py --load "$OUT_DIR/load.csv" -o "$OUT_DIR/load_work_precision.png" \
  --title "$cpu, $(nproc) cores, $(date -u '+%Y-%m-%d')$( ((quick)) && echo ' (--quick smoke run)')"

# 5. the profile
if ((profile)); then
  if command -v valgrind >/dev/null 2>&1 && command -v callgrind_annotate >/dev/null 2>&1; then
    # passes over the case set: enough that program start-up is a small share
    for what in row:3 auto:30; do
      repeat=${what#*:} what=${what%:*}
      raw="$OUT_DIR/callgrind.$what.out"
      log "valgrind --tool=callgrind $BENCH --profile $what --repeat $repeat"
      valgrind --tool=callgrind --callgrind-out-file="$raw" "$BENCH" --profile "$what" \
        --repeat "$repeat" >"$OUT_DIR/profile_$what.log" 2>&1
      {
        echo "# valgrind --tool=callgrind $BENCH --profile $what --repeat $repeat"
        echo "# $(grep '^profile' "$OUT_DIR/profile_$what.log")"
        echo "## exclusive (self) instruction counts"
        callgrind_annotate --auto=no "$raw" 2>/dev/null | sed -n '/file:function/,$p' | sed -n '1,24p'
        echo "## inclusive instruction counts"
        callgrind_annotate --auto=no --inclusive=yes "$raw" 2>/dev/null | sed -n '/file:function/,$p' |
          sed -n '1,24p'
      } >"$OUT_DIR/profile_$what.txt"
    done
  else
    log "valgrind not installed: no profile (apt-get install valgrind)"
  fi
fi

# --publish: what docs/performance.md shows
if ((publish)); then
  cp "$OUT_DIR/bench.md" "$OUT_DIR/bench.csv" "$OUT_DIR/history.csv" "$OUT_DIR/load.csv" \
    "$OUT_DIR/work_precision.png" "$OUT_DIR/load_work_precision.png" tools/bench/
  log "copied bench.md, bench.csv, history.csv, load.csv, work_precision.png," \
    "load_work_precision.png to tools/bench/"
fi

log "wrote $OUT_DIR/{bench.csv,bench_cases.csv,bench.md,history.csv,load.csv,work_precision.png,load_work_precision.png,machine.txt}"
sed -n '/^### Targets/,/^### Error estimates/p' "$OUT_DIR/bench.md" | sed '$d'
sed -n '/^## Velocity histories/,$p' "$OUT_DIR/bench.md"
