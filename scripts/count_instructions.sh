#!/bin/bash
# Exact host instruction count of one frame of the demo scene (valgrind --tool=callgrind,
# counting only inside render_frame: begin_frame + draw + render, no file loading), of a frame
# of a small moving object over a still scene with and without skipping unchanged strips, and of
# the Cortex-M budget cases of the benchmark firmware's host build, when that is built in the tree.
# With --write-docs the figures also go to docs/measurements/count_instructions.md as a table
# (scripts/write_measurements.py).
# Usage: scripts/count_instructions.sh [--write-docs] [build dir, default build/release]
set -euo pipefail
cd "$(dirname "$0")/.."
write_docs=0
args=()
for a in "$@"; do
  if [[ $a == --write-docs ]]; then write_docs=1; else args+=("$a"); fi
done
build=${args[0]:-build/release}
# Table rows for --write-docs: | frame | what the benchmark printed | instructions |
rows=()
bench="$build/tests/bench/lr_frame_bench"
[ -x "$bench" ] || { echo "count_instructions: $bench not built (cmake --preset release && cmake --build --preset release)"; exit 1; }
command -v valgrind >/dev/null || { echo "count_instructions: valgrind is not installed (apt-get install valgrind)"; exit 1; }
out=$(mktemp -d)
valgrind --tool=callgrind --callgrind-out-file="$out/cg.out" --collect-atstart=no \
  --toggle-collect='*render_frame*' "$bench" --frame-once >"$out/stdout" 2>"$out/stderr" || { cat "$out/stderr"; exit 1; }
cat "$out/stdout"
ir=$(grep -E '^summary:|^totals:' "$out/cg.out" | head -1 | awk '{print $2}')
echo "host instructions per frame (callgrind Ir, x86-64): $ir"
rows+=("| demo scene | $(tr '\n' ' ' <"$out/stdout") | $ir |")
# Skipping unchanged strips: the knot still, a small cube circling in front of it; the eleventh
# frame counted, rendered with and without strip input signatures.
# "signed" counts the first frame with strip signatures (nothing to leave out yet): their cost.
for mode in full skip signed; do
  valgrind --tool=callgrind --callgrind-out-file="$out/cg_$mode.out" --collect-atstart=no \
    --toggle-collect='*counted_moving_frame*' "$bench" --moving-once "$mode" >"$out/stdout" 2>"$out/stderr" \
    || { cat "$out/stderr"; exit 1; }
  ir=$(grep -E '^summary:|^totals:' "$out/cg_$mode.out" | head -1 | awk '{print $2}')
  echo "moving cube over the still knot, $mode: $(cat "$out/stdout"); host instructions per frame: $ir"
  rows+=("| moving cube over the still knot, $mode | $(tr '\n' ' ' <"$out/stdout") | $ir |")
done

# The Cortex-M budget cases on the host: the benchmark firmware built for the host
# (tests/firmware_host/lr_bench_host), one callgrind dump each time lr_bench_marker is entered, so
# that a case's measured frame (between its two markers, the region scripts/bench_cortex_m.sh
# counts under QEMU) is the dump made at its second marker: dump 2i + 2 for case i.
bench_host="$build/tests/firmware_host/lr_bench_host"
if [ -x "$bench_host" ]; then
  valgrind --tool=callgrind --callgrind-out-file="$out/bench.out" --dump-before=lr_bench_marker \
    "$bench_host" >"$out/bench_stdout" 2>"$out/bench_stderr" || { cat "$out/bench_stderr"; exit 1; }
  echo "host instructions per frame of the Cortex-M budget cases (callgrind Ir, x86-64, $bench_host):"
  i=0
  while read -r name; do
    dump="$out/bench.out.$((2 * i + 2))"
    i=$((i + 1))
    case "$name" in
      knot_gouraud_cullback | cube_nearest | cube_bilinear | ground_nearest | knot64k_gouraud) ;;
      *) continue ;;
    esac
    [ -f "$dump" ] || { echo "count_instructions: no callgrind dump $dump for $name"; exit 1; }
    ir=$(grep -E '^summary:|^totals:' "$dump" | head -1 | awk '{print $2}')
    printf '  %-16s %s\n' "$name" "$ir"
    rows+=("| Cortex-M budget case $name (lr_bench_host) | | $ir |")
  done < <(awk '/^lr_bench: case / { print $3 }' "$out/bench_stdout")
else
  echo "count_instructions: $bench_host not built: no host counts of the Cortex-M budget cases" \
    "(cmake --build $build --target lr_bench_host)"
fi
rm -rf "$out"
if ((write_docs)); then
  {
    echo "Host instructions per frame (callgrind Ir, x86-64, $build)."
    echo
    echo "| frame | benchmark output | instructions |"
    echo "|---|---|---:|"
    printf '%s\n' "${rows[@]}"
  } | python3 scripts/write_measurements.py count_instructions "bash scripts/count_instructions.sh --write-docs" \
    "Host instruction counts"
fi
