#!/bin/bash
# Quality benchmark: time, instructions, RAM and error against the double reference for
# every quality setting of the core on five 320x240 scenes (knot, sphere, clipped ground plane,
# textured cube, textured ground plane to the horizon; see tests/bench/quality_bench.cpp).
#   1. builds the release configuration's lr_quality_bench and lr_quality_scenes, and the
#      Cortex-M4F tree's lr_quality (firmware/quality: the same frames, checked against the host's);
#   2. `--table`: pixels, host time per frame (median of 21 runs), RAM and the error metrics per
#      (scene, setting) -> build/release/quality_bench_raw.csv;
#   3. lr_quality under QEMU (mps2-an386) with the instruction-counting plugin: the exact
#      Cortex-M4F instructions of each configuration's frame (begin_frame, draws, render), the
#      benchmark's instruction axis;
#   4. joins them into build/release/quality_bench.csv, then scripts/plot_quality.py writes
#      build/release/quality_bench.md (+ .json), the plot build/release/quality_pareto.png
#      (LR_PLOT_OUT=docs/images/quality_pareto.png to refresh the README's) and prints the
#      Pareto front of each scene (instructions against mean error). With --write-docs the
#      table also goes to docs/measurements/quality_bench.md (scripts/write_measurements.py)
#      and the plot to docs/images/quality_pareto.png, the README's.
# Benchmarks print figures; they never pass or fail on time.
# Usage: scripts/quality_bench.sh [--write-docs]
#   LR_QUALITY_M4_TREE  the Cortex-M4F build tree (default build/cortex-m4f)
#   LR_QUALITY_BEFORE   an earlier run's quality_bench.csv: its Pareto fronts are drawn dashed
#                       (default docs/measurements/quality_bench_m4f_before.csv if present)
set -euo pipefail
cd "$(dirname "$0")/.."
write_docs=0
for a in "$@"; do
  if [[ $a == --write-docs ]]; then write_docs=1; else echo "usage: scripts/quality_bench.sh [--write-docs]" >&2; exit 2; fi
done
build=build/release
bench="$build/tests/bench/lr_quality_bench"
raw="$build/quality_bench_raw.csv"
csv="$build/quality_bench.csv"

# Debian's python3-matplotlib lives in /usr/bin/python3 (another python3 may come first in PATH).
py=python3
[ -x /usr/bin/python3 ] && py=/usr/bin/python3
"$py" -c 'import matplotlib' 2>/dev/null ||
  { echo "quality_bench: python3-matplotlib is not installed (bash scripts/setup.sh test)"; exit 1; }
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)" --target lr_quality_bench lr_quality_scenes
# The Cortex-M4F image of the same frames (firmware/quality), its scenes made by lr_quality_scenes.
m4_tree=${LR_QUALITY_M4_TREE:-build/cortex-m4f}
[[ -f $m4_tree/CMakeCache.txt ]] ||
  LR_HOST_TOOLS_DIR=$PWD/$build cmake --preset cortex-m4f -B "$m4_tree" >/dev/null
cmake --build "$m4_tree" -j"$(nproc)" --target lr_quality ||
  { echo "quality_bench: cannot build lr_quality in $m4_tree (configure it with LR_HOST_TOOLS_DIR naming a host tree with lr_quality_scenes built, e.g. LR_HOST_TOOLS_DIR=\$PWD/$build)"; exit 1; }
read -r _ _ m4_machine m4_elf < <(grep '^lr_quality ' "$m4_tree/firmware/images.txt") ||
  { echo "quality_bench: no lr_quality image in $m4_tree/firmware/images.txt"; exit 1; }

echo "== host time, RAM and error against the double reference ($raw)"
"$bench" --table "$raw"

echo "== Cortex-M4F instructions per frame (QEMU, $m4_elf)"
run="$(bash scripts/icount.sh --machine "$m4_machine" "$m4_elf" lr_bench_marker)" ||
  { echo "$run" >&2; echo "quality_bench: lr_quality failed under QEMU" >&2; exit 1; }
grep -q '^lr_quality: PASS' <<<"$run" ||
  { grep 'DIFFERS' <<<"$run" >&2; echo "quality_bench: the Cortex-M4F frames differ from the host's" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# One "KEY COUNT" line per configuration (key: the seven columns joined by '.').
awk '
  BEGIN { n = 0; c = 0 }
  /^icount: marker / { counts[n++] = $NF }
  /^lr_quality: case / { key[c++] = $3 "." $4 "." $5 "." $6 "." $7 "." $8 "." $9 }
  END {
    if (n != 2 * c) { print "quality_bench: marker count " n " != 2 x " c " cases" > "/dev/stderr"; exit 1 }
    for (i = 0; i < c; i++) print key[i], counts[2 * i + 1] - counts[2 * i]
  }' <<<"$run" >"$tmp/counts"

# Insert instructions_per_frame (the Cortex-M4F count) after host_ns_per_frame (column 10).
awk -F, -v OFS=, -v counts="$tmp/counts" '
  BEGIN { while ((getline l < counts) > 0) { split(l, f, " "); n[f[1]] = f[2] } }
  NR == 1 { $10 = $10 ",instructions_per_frame"; print; next }
  {
    k = $1 "." $2 "." $3 "." $4 "." $5 "." $6 "." $7
    if (!(k in n)) { print "quality_bench: no Cortex-M4F count for " k > "/dev/stderr"; exit 1 }
    $10 = $10 "," n[k]
    print
  }' "$raw" >"$csv"

echo "== table, plot and Pareto fronts"
plot_default=$build/quality_pareto.png
((write_docs)) && plot_default=docs/images/quality_pareto.png
before=${LR_QUALITY_BEFORE:-docs/measurements/quality_bench_m4f_before.csv}
before_arg=()
[[ -f $before ]] && before_arg=("$before")
"$py" scripts/plot_quality.py "$csv" "${LR_PLOT_OUT:-$plot_default}" "${before_arg[@]}"
if ((write_docs)); then
  python3 scripts/write_measurements.py quality_bench "bash scripts/quality_bench.sh --write-docs" \
    "Accuracy and stability: every quality setting" <"$build/quality_bench.md"
fi
