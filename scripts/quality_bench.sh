#!/bin/bash
# Quality benchmark: time, instructions, RAM and error against the double reference for
# every quality setting of the core on five 320x240 scenes (knot, sphere, clipped ground plane,
# textured cube, textured ground plane to the horizon; see tests/bench/quality_bench.cpp).
#   1. builds the release configuration's lr_quality_bench;
#   2. `--table`: pixels, host time per frame (median of 21 runs), RAM and the error metrics per
#      (scene, setting) -> build/release/quality_bench_raw.csv;
#   3. callgrind per configuration (counting only inside quality_bench_frame: begin_frame, draws,
#      render), JOBS at a time -> exact host instructions per frame (x86-64);
#   4. joins them into build/release/quality_bench.csv, then scripts/plot_quality.py writes
#      build/release/quality_bench.md (+ .json), the plot build/release/quality_pareto.png
#      (LR_PLOT_OUT=docs/images/quality_pareto.png to refresh the README's) and prints the
#      Pareto front of each scene (instructions against mean error). With --write-docs the
#      table also goes to docs/measurements/quality_bench.md (scripts/write_measurements.py)
#      and the plot to docs/images/quality_pareto.png, the README's.
# Benchmarks print figures; they never pass or fail on time.
# Usage: scripts/quality_bench.sh [--write-docs] [jobs for the callgrind runs, default 2]
set -euo pipefail
cd "$(dirname "$0")/.."
write_docs=0
args=()
for a in "$@"; do
  if [[ $a == --write-docs ]]; then write_docs=1; else args+=("$a"); fi
done
jobs=${args[0]:-2}
build=build/release
bench="$build/tests/bench/lr_quality_bench"
raw="$build/quality_bench_raw.csv"
csv="$build/quality_bench.csv"

command -v valgrind >/dev/null || { echo "quality_bench: valgrind is not installed (apt-get install valgrind)"; exit 1; }
# Debian's python3-matplotlib lives in /usr/bin/python3 (another python3 may come first in PATH).
py=python3
[ -x /usr/bin/python3 ] && py=/usr/bin/python3
"$py" -c 'import matplotlib' 2>/dev/null ||
  { echo "quality_bench: python3-matplotlib is not installed (bash scripts/setup.sh test)"; exit 1; }
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)" --target lr_quality_bench

echo "== host time, RAM and error against the double reference ($raw)"
"$bench" --table "$raw"

echo "== callgrind, one frame per configuration ($jobs at a time)"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$bench" --list >"$tmp/configs"

# count DIR SCENE SHADING PERSP STRIP FILTER MIP FORMAT: the instruction count -> DIR/ir.KEY
count() {
  local dir=$1
  shift
  local key
  key=$(IFS=.; echo "$*")
  if ! valgrind --tool=callgrind --callgrind-out-file="$dir/cg.$key" --collect-atstart=no \
    --toggle-collect='*quality_bench_frame*' "$bench" --once "$@" >"$dir/out.$key" 2>"$dir/err.$key"; then
    echo "quality_bench: callgrind run failed: --once $*" >&2
    cat "$dir/out.$key" "$dir/err.$key" >&2
    return 1
  fi
  grep -E '^summary:|^totals:' "$dir/cg.$key" | head -1 | awk '{print $2}' >"$dir/ir.$key"
  rm -f "$dir/cg.$key"
}
export -f count
export bench
xargs -P "$jobs" -L 1 bash -c 'count "$@"' _ "$tmp" <"$tmp/configs"

# Insert instructions_per_frame after host_ns_per_frame (column 10).
awk -F, -v OFS=, -v dir="$tmp" '
  NR == 1 { $10 = $10 ",instructions_per_frame"; print; next }
  {
    f = dir "/ir." $1 "." $2 "." $3 "." $4 "." $5 "." $6 "." $7
    if ((getline n < f) <= 0) { print "quality_bench: no count for " f > "/dev/stderr"; exit 1 }
    close(f)
    $10 = $10 "," n
    print
  }' "$raw" >"$csv"

echo "== table, plot and Pareto fronts"
plot_default=$build/quality_pareto.png
((write_docs)) && plot_default=docs/images/quality_pareto.png
"$py" scripts/plot_quality.py "$csv" "${LR_PLOT_OUT:-$plot_default}"
if ((write_docs)); then
  python3 scripts/write_measurements.py quality_bench "bash scripts/quality_bench.sh --write-docs" \
    "Accuracy and stability: every quality setting" <"$build/quality_bench.md"
fi
