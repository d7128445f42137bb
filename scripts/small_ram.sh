#!/usr/bin/env bash
# The peer bunnies and the 64,000-triangle knot in small RAM, drawn in bands (firmware/peer/
# small_ram.cpp): lr_peer_bunny_16k, S1 (3,674 triangles) in 16 KB — on Cortex-M0+ on the
# micro:bit, whose RAM is 16 KB in all — and lr_peer_bunnyx_64k, S1x (58,784 triangles), and
# lr_peer_knot64k_64k, lr_bench's knot64k_gouraud (64,000 triangles), in 64 KB on Cortex-M4F;
# and lr_peer_bunny_64k, S1 in 64 KB in one pass (the program fails if it needs a second band).
# Runs each image of each bare-metal tree under QEMU with the instruction-counting plugin
# (scripts/icount.sh) and checks
#   1. the run passes: no store dropped work, every strip arrived;
#   2. its frame checksum is the scene's in lr_peer_host or lr_bench_host (the one-pass frame,
#      strips of 8, stores for the whole mesh), and its PPM file is byte for byte the one the
#      host build of the same program writes (lr_peer_<name>_host);
#   3. its RAM (.data + .bss + the stack the linker script reserves) is within the case's budget,
#      and the reserved stack covers the static worst case (scripts/stack_usage.py).
# Then prints one Markdown table: instructions of the frame (between the program's two
# lr_bench_marker() calls), bands, stores, RAM and worst-case stack.
#
# Usage: scripts/small_ram.sh [--write-docs] [build tree ...]
#          (default: build/cortex-m0plus build/cortex-m4f, those that exist)
#   --write-docs      also writes docs/measurements/small_ram.md (scripts/write_measurements.py)
#   LR_HOST_DIR       the host build's firmware_host folder (default build/debug/tests/firmware_host)
#   LR_ICOUNT_PLUGIN  the plugin (scripts/icount.sh's default otherwise)
# Files go to out/small_ram/. Exit status 0 when every check holds, 1 otherwise (why, on
# stderr). Figures are printed, never compared with a threshold.
set -euo pipefail
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
# shellcheck source=scripts/lib/firmware_rules.sh
source scripts/lib/firmware_rules.sh

fail() {
  echo "small_ram: FAIL: $*" >&2
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

host_dir="${LR_HOST_DIR:-build/debug/tests/firmware_host}"
host_dir="$(cd "$host_dir" 2>/dev/null && pwd)" || fail "${LR_HOST_DIR:-build/debug/tests/firmware_host} missing (cmake --preset debug and build)"
for exe in lr_peer_host lr_bench_host; do
  [[ -x "$host_dir/$exe" ]] || fail "$host_dir/$exe not built"
done
plugin_args=()
[[ -n "${LR_ICOUNT_PLUGIN:-}" ]] && plugin_args=(--plugin "$LR_ICOUNT_PLUGIN")
out=out/small_ram
mkdir -p "$out"
# The one-pass frames' case lines: the peer scenes', and lr_bench's (the knot).
one_pass_log="$("$host_dir/lr_peer_host")"$'\n'"$("$host_dir/lr_bench_host")"

# The host build's frame of an image (run once per image name): its PPM in $out/host/<name>/ and
# its case line, checked against the one-pass frame of lr_peer_host or lr_bench_host. Prints the
# checksum.
declare -A host_sums=()
host_frame() {
  local name="$1" dir="$out/host/$1" sum case_name one_pass
  mkdir -p "$dir"
  [[ -x "$host_dir/${name}_host" ]] || fail "$host_dir/${name}_host not built"
  (cd "$dir" && rm -f "$name.ppm" && "$host_dir/${name}_host" >log.txt) \
    || fail "${name}_host failed: $(tail -2 "$dir/log.txt")"
  read -r case_name sum < <(awk '$1 == "lr_bench:" && $2 == "case" { print $3, $5 }' "$dir/log.txt")
  one_pass="$(awk -v c="${case_name%-*}" '$1 == "lr_bench:" && $3 == c { print $5 }' <<<"$one_pass_log")"
  [[ -n "$one_pass" ]] || fail "neither lr_peer_host nor lr_bench_host printed a ${case_name%-*} case"
  [[ "$sum" == "$one_pass" ]] || fail "${name}_host: the banded frame ($sum) is not the one-pass ${case_name%-*} frame ($one_pass)"
  echo "$sum"
}

rows=()
for tree in "${trees[@]}"; do
  list="$tree/firmware/images.txt"
  [[ -f "$list" ]] || fail "$list missing (configure and build $tree)"
  core="$(basename "$tree")"
  found=0
  while read -r name board machine elf; do
    [[ "$name" =~ ^lr_peer_(bunny_16k|bunny_64k|bunnyx_64k|knot64k_64k)$ ]] || continue
    found=1
    [[ -f "$elf" ]] || fail "$elf not built (cmake --build $tree --target $name)"
    [[ -n "${host_sums[$name]:-}" ]] || host_sums[$name]="$(host_frame "$name")"
    want="${host_sums[$name]}"
    run="$out/$core"
    mkdir -p "$run"
    rm -f "$run/$name.ppm"
    elf_abs="$(cd "$(dirname "$elf")" && pwd)/$(basename "$elf")"
    log="$(cd "$run" && bash "$repo_root/scripts/icount.sh" "${plugin_args[@]}" --machine "$machine" \
      "$elf_abs" lr_bench_marker 2>&1)" || { echo "$log" >&2; fail "$name on $board ($core) failed"; }
    grep -q "^$name: PASS" <<<"$log" || { echo "$log" >&2; fail "$name on $board: no PASS"; }
    read -r case_name sum < <(awk '$1 == "lr_bench:" && $2 == "case" { print $3, $5 }' <<<"$log")
    [[ "$sum" == "$want" ]] || fail "$name on $board: checksum $sum, the one-pass frame's is $want"
    cmp -s "$run/$name.ppm" "$out/host/$name/$name.ppm" \
      || fail "$name on $board: frame differs from the host's ($(cmp "$run/$name.ppm" "$out/host/$name/$name.ppm" 2>&1 | head -1))"
    mapfile -t marks < <(awk '$1 == "icount:" && $2 == "marker" { print $NF }' <<<"$log")
    [[ ${#marks[@]} -eq 2 ]] || fail "$name on $board: expected 2 marker lines, got ${#marks[@]}"
    instructions=$((marks[1] - marks[0]))
    stats="$(grep "^$name: pixels_written" <<<"$log" | head -1)"
    stat() { awk -v k="$1" '{ for (i = 1; i < NF; ++i) if ($i == k) print $(i + 1) }' <<<"$stats"; }
    read -r data bss stack < <(arm-none-eabi-size -A "$elf" | awk '
      $1 == ".data" { d = $2 } $1 == ".bss" { b = $2 } $1 == ".stack" { s = $2 }
      END { print d + 0, b + 0, s + 0 }')
    worst="$(python3 scripts/stack_usage.py "$elf" "$tree" --vector-table .isr_vector --entry main \
      "${lr_fw_stack_rules[@]}" --tool-prefix arm-none-eabi- --machine 2>&1)" \
      || fail "$name ($board): stack analysis failed: $worst"
    worst="$(awk -F'\t' '$1 == "total" { print $2 }' <<<"$worst")"
    [[ -n "$worst" ]] || fail "$name ($board): no stack total"
    ((worst <= stack)) || fail "$name ($board): worst-case stack $worst B > the $stack B reserved"
    ram=$((data + bss + stack))
    budget="$(stat ram_budget)"
    ((ram <= budget)) || fail "$name ($board): RAM $ram B > its budget of $budget B"
    echo "small_ram: $name ($case_name) on $board ($core): frame = the one-pass frame ($sum), = the host's PPM; $instructions instructions, $(stat bands) bands; RAM $ram B of $budget B"
    rows+=("| $case_name | $core | $board | $(commas "$instructions") | $(stat bands) | $(stat band_retries) | $(stat strip_passes) | $(stat strip_rows) | $(stat vertex_store) / $(stat triangle_store) / $(stat active_store) | $(commas "$(stat store_bytes)") | $(commas "$(stat strip_bytes)") | $(commas "$(stat renderer_bytes)") | $(commas $((data + bss))) | $(commas "$stack") ($(commas "$worst")) | $(commas "$ram") of $(commas "$budget") |")
  done <"$list"
  ((found)) || fail "$tree builds neither lr_peer_bunny_16k nor lr_peer_bunnyx_64k"
done

table="$(
  echo "## The peer bunnies and the 64,000-triangle knot in small RAM (firmware/peer/small_ram.cpp)"
  echo
  echo "S1 (the bunny, 1,839 vertices and 3,674 triangles), S1x (subdivided twice, 29,394"
  echo "vertices and 58,784 triangles) and lr_bench's knot64k_gouraud (the torus knot subdivided"
  echo "twice, 32,841 vertices and 64,000 triangles), from flash in spatial order"
  echo "(\`lineraster-asset --locality\`), at 320x240 RGB565, drawn in bands. Every frame below is"
  echo "its scene's one-pass frame (the checksum of lr_peer's or lr_bench's case) and the host"
  echo "build's PPM byte for byte."
  echo
  echo "| case | core | board | instructions | bands | band retries | strip passes | strip rows | stores: vertices / binned / active | stores (B) | strip buffers (B) | renderer (B) | .data + .bss (B) | stack reserved (worst case) | RAM in all (B) |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
)"
echo "$table"
if ((write_docs)); then
  echo "$table" | python3 scripts/write_measurements.py small_ram "bash scripts/small_ram.sh --write-docs" \
    "The peer bunnies and the knot in small RAM (S1 in the micro:bit's 16 KB, S1x and the 64,000-triangle knot in 64 KB)"
fi
echo "small_ram: PASS (${#trees[@]} trees)"
