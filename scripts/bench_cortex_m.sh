#!/usr/bin/env bash
# Instruction budgets on Cortex-M: runs lr_bench (firmware/bench) of each bare-metal build tree
# under QEMU with the instruction-counting plugin (scripts/icount.sh, tools/qemu_icount) and
# prints, per case, the exact Thumb instructions of one 320x240 frame, per pixel written and per
# input triangle, and the frame rate a core would reach at 1.0 and 1.5 cycles per instruction,
# next to the SPI limit. Also checks that every case's frame checksum equals the host build's
# (lr_bench_host), i.e. the measured frames are the host's frames. Then, per tree, the early-out
# table and the cost-per-feature table (scripts/bench_tables.py: differences of the cases'
# counts, solved as it explains).
# Benchmark figures: printed, never compared with a threshold.
#
# Usage: scripts/bench_cortex_m.sh [--write-docs] [build tree ...]
#          (default: build/cortex-m4f build/cortex-m0plus)
#   LR_BENCH_HOST  the host build of the benchmark (default build/debug/tests/firmware_host/lr_bench_host)
#   LR_ICOUNT_PLUGIN  the plugin (scripts/icount.sh's default otherwise)
# Tables also go to out/bench_cortex_m/<tree>.md and, with --write-docs, all trees' to
# docs/measurements/bench_cortex_m.md (scripts/write_measurements.py).
set -euo pipefail
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

fail() {
  echo "bench_cortex_m: FAIL: $*" >&2
  exit 1
}
host_bench="${LR_BENCH_HOST:-build/debug/tests/firmware_host/lr_bench_host}"
[[ -x "$host_bench" ]] || fail "$host_bench not built (cmake --build --preset debug --target lr_bench_host)"
host_out="$("$host_bench")" || fail "the host build of the benchmark failed: $host_out"

write_docs=0
trees=()
for a in "$@"; do
  if [[ $a == --write-docs ]]; then write_docs=1; else trees+=("$a"); fi
done
[[ ${#trees[@]} -gt 0 ]] || trees=(build/cortex-m4f build/cortex-m0plus)
mkdir -p out/bench_cortex_m
tables=()

# 320 x 240 RGB565 = 1,228,800 bits per frame on a 62.5 MHz SPI clock.
spi_fps="$(awk 'BEGIN { printf "%.1f", 62.5e6 / (320 * 240 * 16) }')"

for tree in "${trees[@]}"; do
  list="$tree/firmware/images.txt"
  [[ -f "$list" ]] || fail "$list missing (configure and build $tree: scripts/ci_cross.sh)"
  read -r _ board machine elf < <(grep '^lr_bench ' "$list") || fail "no lr_bench image in $list"
  core="$(basename "$tree")"
  case "$core" in
    cortex-m0plus) mhz=133; cpu="Cortex-M0+ (ARMv6-M; counted on QEMU $machine)" ;;
    cortex-m4f) mhz=168; cpu="Cortex-M4F" ;;
    *) mhz=168; cpu="$core" ;;
  esac
  run="$(bash scripts/icount.sh --machine "$machine" "$elf" lr_bench_marker)" \
    || { echo "$run" >&2; fail "lr_bench failed under QEMU ($tree)"; }
  # Checksums: each case line must equal the host's.
  target_cases="$(grep '^lr_bench: case ' <<<"$run")"
  host_cases="$(grep '^lr_bench: case ' <<<"$host_out")"
  [[ -n "$target_cases" && "$target_cases" == "$host_cases" ]] \
    || fail "$core frames differ from the host's:"$'\n'"$(diff <(echo "$host_cases") <(echo "$target_cases") || true)"
  table="out/bench_cortex_m/$core.md"
  {
    echo "**$cpu**, 320x240 RGB565, strips of 8 rows (frame = begin_frame + draws + render; the sink does no per-pixel work). fps at $mhz MHz; the SPI limit (62.5 MHz, full frames) is $spi_fps fps."
    echo
    echo "| case | pixels | triangles | instructions per frame | per pixel | per triangle | fps at 1.0 CPI | fps at 1.5 CPI |"
    echo "|---|---:|---:|---:|---:|---:|---:|---:|"
    awk -v mhz="$mhz" '
      BEGIN { n = 0; c = 0 }
      /^icount: marker / { counts[n++] = $NF }
      /^lr_bench: case / { name[c] = $3; px[c] = $7; tri[c] = $9; c++ }
      function commas(v,   s) { s = sprintf("%.0f", v); while (s ~ /[0-9][0-9][0-9][0-9]/) sub(/[0-9][0-9][0-9]($|,)/, ",&", s); return s }
      END {
        if (n != 2 * c) { print "marker count " n " != 2 x " c " cases" > "/dev/stderr"; exit 1 }
        for (i = 0; i < c; i++) {
          ins = counts[2 * i + 1] - counts[2 * i]
          # The early-out cases may write no pixel or draw no triangle.
          ppx = px[i] > 0 ? commas(ins / px[i] + 0.5) : "-"
          ptri = tri[i] > 0 ? commas(ins / tri[i] + 0.5) : "-"
          printf "| %s | %s | %s | %s | %s | %s | %.1f | %.1f |\n", name[i], commas(px[i]), commas(tri[i]), commas(ins), ppx, ptri, mhz * 1e6 / ins, mhz * 1e6 / (1.5 * ins)
        }
      }' <<<"$run" || fail "could not pair the marker counts with the cases ($tree)"
  } >"$table"
  # The Cortex-M4F budgets of the "Skip what a scene doesn't need" issue, next to the figures
  # (printed, not asserted): instructions per 320x240 frame.
  if [[ "$core" == cortex-m4f ]]; then
    {
      echo
      echo "| budget scene | case | instructions | budget | ratio |"
      echo "|---|---|---:|---:|---:|"
      awk '
        BEGIN {
          n = 0; c = 0
          budget["knot_gouraud_cullback"] = 1600000; what["knot_gouraud_cullback"] = "closed Gouraud mesh (back faces culled), ~3,700 triangles, ~22,000 pixels"
          budget["cube_nearest"] = 850000; what["cube_nearest"] = "perspective-correct textured cube, ~40,000 pixels, nearest"
          budget["cube_bilinear"] = 2000000; what["cube_bilinear"] = "the same cube, bilinear"
          budget["ground_nearest"] = 800000; what["ground_nearest"] = "ground plane to the horizon, nearest"
          budget["knot64k_gouraud"] = 16000000; what["knot64k_gouraud"] = "the knot subdivided twice, 64,000 triangles, Gouraud, back faces culled"
        }
        /^icount: marker / { counts[n++] = $NF }
        /^lr_bench: case / { name[c++] = $3 }
        function commas(v,   s) { s = sprintf("%.0f", v); while (s ~ /[0-9][0-9][0-9][0-9]/) sub(/[0-9][0-9][0-9]($|,)/, ",&", s); return s }
        END {
          for (i = 0; i < c; i++) {
            if (!(name[i] in budget)) continue
            ins = counts[2 * i + 1] - counts[2 * i]
            printf "| %s | %s | %s | %s | %.2f |\n", what[name[i]], name[i], commas(ins), commas(budget[name[i]]), ins / budget[name[i]]
          }
        }' <<<"$run"
    } >>"$table"
  fi
  # The early-out and cost-per-feature tables, from the same markers (scripts/bench_tables.py).
  {
    echo
    python3 scripts/bench_tables.py <<<"$run"
  } >>"$table" || fail "could not compute the early-out and feature tables ($tree)"
  cat "$table"
  echo
  echo "bench_cortex_m: $core: $(grep -c '^lr_bench: case ' <<<"$run") frames identical to the host's"
  tables+=("$table")
done

if ((write_docs)); then
  for table in "${tables[@]}"; do
    echo "## $(basename "$table" .md)"
    echo
    cat "$table"
    echo
  done | python3 scripts/write_measurements.py bench_cortex_m "bash scripts/bench_cortex_m.sh --write-docs" \
    "Instructions per frame on Cortex-M"
fi
