#!/bin/bash
# Lighting benchmark: per shading mode (flat, Gouraud, Phong exact, Phong with a
# normal-indexed lighting table of 16..256 cells, nearest or bilinear) on a sphere and on the
# torus knot (320x240, RGB565 strips of 8):
#   1. builds the release configuration's lr_lighting_bench;
#   2. `--table`: lit pixels, RAM of the mode's stores, error against the double reference of the
#      same shading and of Phong -> build/release/lighting_bench_raw.csv; prints what SLERP
#      would change (double reference only);
#   3. callgrind per configuration (counting only inside lighting_bench_frame: begin_frame,
#      draws with their lighting tables, render), JOBS at a time -> exact host instructions;
#   4. prints a table: instructions per frame, per lit pixel, the extra per lit pixel over
#      Gouraud, PSNR -> build/release/lighting_bench.md (and, with --write-docs,
#      docs/measurements/lighting_bench.md: scripts/write_measurements.py).
# Benchmarks print figures; they never pass or fail on time.
# Usage: scripts/lighting_bench.sh [--write-docs] [jobs for the callgrind runs, default 2]
set -euo pipefail
cd "$(dirname "$0")/.."
write_docs=0
args=()
for a in "$@"; do
  if [[ $a == --write-docs ]]; then write_docs=1; else args+=("$a"); fi
done
jobs=${args[0]:-2}
build=build/release
bench="$build/tests/bench/lr_lighting_bench"
raw="$build/lighting_bench_raw.csv"
md="$build/lighting_bench.md"

command -v valgrind >/dev/null || { echo "lighting_bench: valgrind is not installed (apt-get install valgrind)"; exit 1; }
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)" --target lr_lighting_bench

echo "== error against the double reference ($raw)"
"$bench" --table "$raw"

echo "== callgrind, one frame per configuration ($jobs at a time)"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$bench" --list >"$tmp/configs"
count() {
  local dir=$1 scene=$2 mode=$3
  if ! valgrind --tool=callgrind --callgrind-out-file="$dir/cg.$scene.$mode" --collect-atstart=no \
    --toggle-collect='*lighting_bench_frame*' "$bench" --once "$scene" "$mode" >"$dir/out.$scene.$mode" 2>"$dir/err.$scene.$mode"; then
    echo "lighting_bench: callgrind run failed: --once $scene $mode" >&2
    cat "$dir/err.$scene.$mode" >&2
    return 1
  fi
  grep -E '^summary:|^totals:' "$dir/cg.$scene.$mode" | head -1 | awk '{print $2}' >"$dir/ir.$scene.$mode"
  rm -f "$dir/cg.$scene.$mode"
}
export -f count
export bench
xargs -P "$jobs" -L 1 bash -c 'count "$@"' _ "$tmp" <"$tmp/configs"

python3 - "$raw" "$tmp" "$md" <<'PY'
import csv, os, sys
raw, tmp, md = sys.argv[1:4]
rows = list(csv.DictReader(open(raw)))
ir = {}
for r in rows:
    ir[(r["scene"], r["mode"])] = int(open(os.path.join(tmp, f"ir.{r['scene']}.{r['mode']}")).read())
out = ["| scene | mode | instructions / frame | per lit pixel | extra over Gouraud / lit pixel "
       "| table + surface RAM (B) | PSNR vs own reference (dB) | max err | PSNR vs Phong reference (dB) |",
       "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
for r in rows:
    s, m = r["scene"], r["mode"]
    px = int(r["lit_pixels"])
    n = ir[(s, m)]
    g = ir[(s, "gouraud")]
    out.append(f"| {s} | {m} | {n:,} | {n / px:.1f} | {(n - g) / px:+.1f} | {int(r['mode_ram_bytes']):,} "
               f"| {float(r['psnr_same']):.1f} | {r['max_err_same']} | {float(r['psnr_phong']):.1f} |")
text = "\n".join(out) + "\n"
open(md, "w").write(text)
print(text)
PY
echo "lighting_bench: table in $md"
if ((write_docs)); then
  python3 scripts/write_measurements.py lighting_bench "bash scripts/lighting_bench.sh --write-docs" \
    "Per-pixel lighting: cost against error" <"$md"
fi
