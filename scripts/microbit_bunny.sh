#!/usr/bin/env bash
# The peer scene S1 (the bunny, 3,674 triangles) in 16 KB of RAM: runs lr_peer_bunny_16k
# (firmware/peer/bunny_16k.cpp) of each bare-metal tree under QEMU with the instruction-counting
# plugin (scripts/icount.sh) — on Cortex-M0+ on the micro:bit (16 KB of RAM in all), on
# Cortex-M4F on its default board — and checks that
#   1. the run passes: no store dropped work, every strip arrived;
#   2. its frame checksum is S1's in lr_peer_host (the one-pass frame, strips of 8, stores for
#      the whole mesh), and its PPM file is byte for byte the one the host build of the same
#      program writes (lr_peer_bunny_16k_host);
#   3. the stack the linker script reserves covers the static worst case (scripts/stack_usage.py).
# Then prints one Markdown table: instructions of the frame (between the program's two
# lr_bench_marker() calls), bands, RAM (.data + .bss without the stack) and worst-case stack.
#
# Usage: scripts/microbit_bunny.sh [--write-docs] [build tree ...]
#          (default: build/cortex-m0plus build/cortex-m4f, those that exist)
#   --write-docs      also writes docs/measurements/microbit_bunny.md (scripts/write_measurements.py)
#   LR_BUNNY_HOST     default build/debug/tests/firmware_host/lr_peer_bunny_16k_host
#   LR_PEER_HOST      default build/debug/tests/firmware_host/lr_peer_host
#   LR_ICOUNT_PLUGIN  the plugin (scripts/icount.sh's default otherwise)
# Files go to out/microbit_bunny/. Exit status 0 when every check holds, 1 otherwise (why, on
# stderr). Figures are printed, never compared with a threshold.
set -euo pipefail
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
# shellcheck source=scripts/lib/firmware_rules.sh
source scripts/lib/firmware_rules.sh

fail() {
  echo "microbit_bunny: FAIL: $*" >&2
  exit 1
}
# 1234567 -> 1,234,567
commas() { sed ':a;s/\B[0-9]\{3\}\>/,&/;ta' <<<"$1"; }

write_docs=0
trees=()
for a in "$@"; do
  case "$a" in
    --write-docs) write_docs=1 ;;
    -h | --help) sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    -*) fail "unknown option $a (--help)" ;;
    *) trees+=("$a") ;;
  esac
done
if [[ ${#trees[@]} -eq 0 ]]; then
  for t in build/cortex-m0plus build/cortex-m4f; do [[ -d "$t" ]] && trees+=("$t"); done
fi
[[ ${#trees[@]} -gt 0 ]] || fail "no build tree (cmake --preset cortex-m0plus, then build lr_peer_bunny_16k)"

host_bunny="${LR_BUNNY_HOST:-build/debug/tests/firmware_host/lr_peer_bunny_16k_host}"
host_peer="${LR_PEER_HOST:-build/debug/tests/firmware_host/lr_peer_host}"
for p in "$host_bunny" "$host_peer"; do
  [[ -x "$p" ]] || fail "$p not built (cmake --build --preset debug --target $(basename "$p"))"
done
plugin_args=()
[[ -n "${LR_ICOUNT_PLUGIN:-}" ]] && plugin_args=(--plugin "$LR_ICOUNT_PLUGIN")

out=out/microbit_bunny
mkdir -p "$out/host"
host_bunny_abs="$(cd "$(dirname "$host_bunny")" && pwd)/$(basename "$host_bunny")"
(cd "$out/host" && rm -f lr_peer_bunny_16k.ppm && "$host_bunny_abs" >log.txt) \
  || fail "the host build failed: $(tail -2 "$out/host/log.txt")"
s1_sum="$("$host_peer" | awk '$1 == "lr_bench:" && $3 == "S1" { print $5 }')"
host_sum="$(awk '$1 == "lr_bench:" && $3 == "S1-16k" { print $5 }' "$out/host/log.txt")"
[[ -n "$s1_sum" ]] || fail "$host_peer printed no S1 case"
[[ "$host_sum" == "$s1_sum" ]] || fail "the host build's banded frame ($host_sum) is not the one-pass S1 frame ($s1_sum)"

rows=()
for tree in "${trees[@]}"; do
  list="$tree/firmware/images.txt"
  [[ -f "$list" ]] || fail "$list missing (configure and build $tree)"
  read -r name board machine elf < <(awk '$1 == "lr_peer_bunny_16k"' "$list") \
    || fail "$tree builds no lr_peer_bunny_16k"
  [[ -f "$elf" ]] || fail "$elf not built (cmake --build $tree --target lr_peer_bunny_16k)"
  core="$(basename "$tree")"
  run="$out/$core"
  mkdir -p "$run"
  rm -f "$run/lr_peer_bunny_16k.ppm"
  elf_abs="$(cd "$(dirname "$elf")" && pwd)/$(basename "$elf")"
  log="$(cd "$run" && bash "$repo_root/scripts/icount.sh" "${plugin_args[@]}" --machine "$machine" \
    "$elf_abs" lr_bench_marker 2>&1)" || { echo "$log" >&2; fail "$name on $board ($core) failed"; }
  grep -q '^lr_peer_bunny_16k: PASS' <<<"$log" || { echo "$log" >&2; fail "$name on $board: no PASS"; }
  sum="$(awk '$1 == "lr_bench:" && $3 == "S1-16k" { print $5 }' <<<"$log")"
  [[ "$sum" == "$s1_sum" ]] || fail "$name on $board: checksum $sum, the one-pass S1 frame's is $s1_sum"
  cmp -s "$run/lr_peer_bunny_16k.ppm" "$out/host/lr_peer_bunny_16k.ppm" \
    || fail "$name on $board: frame differs from the host's ($(cmp "$run/lr_peer_bunny_16k.ppm" "$out/host/lr_peer_bunny_16k.ppm" 2>&1 | head -1))"
  mapfile -t marks < <(awk '$1 == "icount:" && $2 == "marker" { print $NF }' <<<"$log")
  [[ ${#marks[@]} -eq 2 ]] || fail "$name on $board: expected 2 marker lines, got ${#marks[@]}"
  instructions=$((marks[1] - marks[0]))
  stats="$(grep '^lr_peer_bunny_16k: pixels_written' <<<"$log" | head -1)"
  stat() { awk -v k="$1" '{ for (i = 1; i < NF; ++i) if ($i == k) print $(i + 1) }' <<<"$stats"; }
  # RAM: .data + .bss (the stores, strips, renderer), and the stack the linker script reserves.
  read -r data bss stack < <(arm-none-eabi-size -A "$elf" | awk '
    $1 == ".data" { d = $2 } $1 == ".bss" { b = $2 } $1 == ".stack" { s = $2 }
    END { print d + 0, b + 0, s + 0 }')
  worst="$(python3 scripts/stack_usage.py "$elf" "$tree" --vector-table .isr_vector --entry main \
    "${lr_fw_stack_rules[@]}" --tool-prefix arm-none-eabi- --machine 2>&1)" \
    || fail "$name ($board): stack analysis failed: $worst"
  worst="$(awk -F'\t' '$1 == "total" { print $2 }' <<<"$worst")"
  [[ -n "$worst" ]] || fail "$name ($board): no stack total"
  ((worst <= stack)) || fail "$name ($board): worst-case stack $worst B > the $stack B reserved"
  stores="$(stat vertex_store) vertices, $(stat triangle_store) binned triangles and $(stat active_store) active triangles"
  echo "microbit_bunny: $core on $board: frame = S1 ($sum), = the host's PPM; $instructions instructions, $(stat bands) bands; RAM $((data + bss)) B + stack $stack B (worst case $worst B)"
  rows+=("| $core | $board ($machine) | $(commas "$instructions") | $(stat bands) | $(stat band_retries) | $(stat strip_passes) | $(commas "$(stat vertices)") | $(commas "$(stat store_bytes)") | $(commas "$(stat strip_bytes)") | $(commas "$(stat renderer_bytes)") | $(commas $((data + bss))) | $(commas "$stack") ($(commas "$worst")) | $(commas $((data + bss + stack))) |")
done

table="$(
  echo "## S1 in 16 KB of RAM (lr_peer_bunny_16k)"
  echo
  echo "The bunny (1,839 vertices, 3,674 triangles, from flash; the asset in spatial order,"
  echo "\`lineraster-asset --locality\`) at 320x240 RGB565 in strips of 1 row, stores of $stores."
  echo "Every frame below is the one-pass S1 frame (checksum $s1_sum) and the host's PPM byte for"
  echo "byte."
  echo
  echo "| core | board | instructions | bands | band retries | strip passes | vertices transformed | stores (B) | strip buffers (B) | renderer (B) | .data + .bss (B) | stack reserved (worst case) | RAM in all (B) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
)"
echo "$table"
if ((write_docs)); then
  echo "$table" | python3 scripts/write_measurements.py microbit_bunny "bash scripts/microbit_bunny.sh --write-docs" \
    "The bunny in 16 KB of RAM (micro:bit)"
fi
echo "microbit_bunny: PASS (${#trees[@]} trees)"
