#!/bin/bash
# Exact host instruction count of one frame of the demo scene (valgrind --tool=callgrind,
# counting only inside render_frame: begin_frame + draw + render, no file loading), and a frame
# of a small moving object over a still scene with and without skipping unchanged strips.
# Usage: scripts/count_instructions.sh [build dir, default build/release]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release}
bench="$build/tests/bench/lr_frame_bench"
[ -x "$bench" ] || { echo "count_instructions: $bench not built (cmake --preset release && cmake --build --preset release)"; exit 1; }
command -v valgrind >/dev/null || { echo "count_instructions: valgrind is not installed (apt-get install valgrind)"; exit 1; }
out=$(mktemp -d)
valgrind --tool=callgrind --callgrind-out-file="$out/cg.out" --collect-atstart=no \
  --toggle-collect='*render_frame*' "$bench" --frame-once >"$out/stdout" 2>"$out/stderr" || { cat "$out/stderr"; exit 1; }
cat "$out/stdout"
ir=$(grep -E '^summary:|^totals:' "$out/cg.out" | head -1 | awk '{print $2}')
echo "host instructions per frame (callgrind Ir, x86-64): $ir"
# Skipping unchanged strips: the knot still, a small cube circling in front of it; the eleventh
# frame counted, rendered with and without strip input signatures.
for mode in full skip; do
  valgrind --tool=callgrind --callgrind-out-file="$out/cg_$mode.out" --collect-atstart=no \
    --toggle-collect='*counted_moving_frame*' "$bench" --moving-once "$mode" >"$out/stdout" 2>"$out/stderr" \
    || { cat "$out/stderr"; exit 1; }
  ir=$(grep -E '^summary:|^totals:' "$out/cg_$mode.out" | head -1 | awk '{print $2}')
  echo "moving cube over the still knot, $mode: $(cat "$out/stdout"); host instructions per frame: $ir"
done
rm -rf "$out"
