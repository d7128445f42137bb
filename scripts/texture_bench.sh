#!/bin/bash
# Texture benchmark figures: filter x perspective mode x mip mode on the textured cube
# and on the ground plane to the horizon, 320x240, RGB565 strips of 8 rows into a null sink.
#   1. builds the release configuration's lr_texture_bench;
#   2. `--table`: pixels, host time per frame (median of 15 runs) and error against the double
#      reference per configuration -> build/release/texture_bench.csv;
#   3. callgrind per configuration (counting only inside texture_bench_frame: begin_frame, draws,
#      render) -> exact host instructions per frame, plus an untextured baseline per scene;
#   4. prints a Markdown table, also written to build/release/texture_bench.md (and, with
#      --write-docs, to docs/measurements/texture_bench.md: scripts/write_measurements.py).
# Benchmarks print figures; they never pass or fail on time.
# Usage: scripts/texture_bench.sh [--write-docs] [jobs for the callgrind runs, default: number of CPUs]
set -euo pipefail
cd "$(dirname "$0")/.."
write_docs=0
args=()
for a in "$@"; do
  if [[ $a == --write-docs ]]; then write_docs=1; else args+=("$a"); fi
done
jobs=${args[0]:-$(nproc)}
build=build/release
bench="$build/tests/bench/lr_texture_bench"
csv="$build/texture_bench.csv"
md="$build/texture_bench.md"

command -v valgrind >/dev/null || { echo "texture_bench: valgrind is not installed (apt-get install valgrind)"; exit 1; }
cmake --preset release >/dev/null
cmake --build --preset release -j"$jobs" --target lr_texture_bench

echo "== host time and error against the double reference ($csv)"
"$bench" --table "$csv"

echo "== callgrind, one frame per configuration ($jobs at a time)"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
{
  tail -n +2 "$csv" | cut -d, -f1-4 | tr , ' '
  echo "cube none exact none"
  echo "ground none exact none"
} >"$tmp/configs"

# count SCENE FILTER PERSP MIP: writes the instruction count to $tmp/ir.SCENE.FILTER.PERSP.MIP
count() {
  local key="$2.$3.$4.$5" dir=$1
  shift
  if ! valgrind --tool=callgrind --callgrind-out-file="$dir/cg.$key" --collect-atstart=no \
    --toggle-collect='*texture_bench_frame*' "$bench" --once "$@" >"$dir/out.$key" 2>"$dir/err.$key"; then
    echo "texture_bench: callgrind run failed: --once $*" >&2
    cat "$dir/out.$key" "$dir/err.$key" >&2
    return 1
  fi
  grep -E '^summary:|^totals:' "$dir/cg.$key" | head -1 | awk '{print $2}' >"$dir/ir.$key"
  rm -f "$dir/cg.$key"
}
export -f count
export bench
xargs -P "$jobs" -L 1 bash -c 'count "$@"' _ "$tmp" <"$tmp/configs"

awk -F, -v dir="$tmp" '
  function sep(n,   s) {  # thousands separators
    s = sprintf("%d", n)
    while (s ~ /[0-9][0-9][0-9][0-9]/) sub(/[0-9][0-9][0-9]([,]|$)/, ",&", s)
    return s
  }
  function ir(key,   f, v) {
    f = dir "/ir." key
    if ((getline v < f) <= 0) v = -1
    close(f)
    return v
  }
  NR == 1 {
    print "| scene | filter | perspective | mip | pixels | instructions/frame | instructions/pixel | host µs | max err | mean err | PSNR |"
    print "|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|"
    next
  }
  {
    n = ir($1 "." $2 "." $3 "." $4)
    printf "| %s | %s | %s | %s | %s | %s | %.1f | %.1f | %d | %.3f | %.2f dB |\n", $1, $2, $3, $4,
           sep($5), sep(n), n / $5, $6 / 1000, $7, $8, $9
    pixels[$1] = $5
  }
  END {
    print ""
    printf "Untextured baseline (same geometry and state, no texture, one frame): "
    n = ir("cube.none.exact.none")
    printf "cube %s instructions (%.1f per pixel); ", sep(n), n / pixels["cube"]
    n = ir("ground.none.exact.none")
    printf "ground %s instructions (%.1f per pixel).\n", sep(n), n / pixels["ground"]
    print ""
    print "320x240, RGB565 strips of 8 rows into a null sink; 64x64 RGB565 texture with its mip chain."
    print "Instructions: callgrind Ir inside texture_bench_frame (begin_frame + draws + render), x86-64."
    print "Host time: median of 15 frames (steady_clock). Errors: per channel (0..255) against the double"
    print "reference over the pixels both renderers cover; PSNR over the same pixels. The ground plane is seen"
    print "by a level camera: every screen row has one depth, so the span modes are exact there (only their"
    print "time shows); the cube shows what they cost in error."
  }' "$csv" >"$md"

cat "$md"
if ((write_docs)); then
  python3 scripts/write_measurements.py texture_bench "bash scripts/texture_bench.sh --write-docs" \
    "Texturing: time against error" <"$md"
fi
