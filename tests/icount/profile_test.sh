#!/usr/bin/env bash
# Tests of the plugin's profile (tools/qemu_icount: profile=PATH, profile_begin/_end/_skip/_count)
# and of scripts/icount_profile.py, which attributes a profile to functions, files and folders.
#
# Usage: tests/icount/profile_test.sh PLUGIN_SO image|asm|firmware [ELF]
#   image     the hand-assembled image of plugin_test.sh: the exact profile of the whole run, of
#             begin/end regions, of alternating periods of one address with skip and count; each
#             one's sum equal to the marker difference; rejected profile arguments. Needs only
#             qemu-system-arm.
#   asm       an ELF linked here from assembly files laid out like the repository (core/span,
#             hal/fake, firmware/start) plus an archive outside it (libfake.a), and a C++ function
#             with an inlined helper from another folder: the script's exact tables by function,
#             file and folder. Needs arm-none-eabi-as/-ld/-ar/-g++/-nm/-addr2line and python3.
#   firmware  firmware/icount_check's ELF (given): the profile over its regions sums to the
#             regions' marker differences and to the counts the firmware expects; the loop case's
#             function has exactly its loop's count; one selected period (profile_skip/count).
# Exit status: 0 pass, 1 fail, 77 skip (a tool or the ELF missing).
set -euo pipefail

[[ $# -ge 2 ]] || { echo "usage: $0 PLUGIN_SO image|asm|firmware [ELF]" >&2; exit 1; }
plugin="$1"
mode="$2"
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
profile_py="$repo_root/scripts/icount_profile.py"
fail() {
  echo "profile_test($mode): FAIL: $*" >&2
  exit 1
}
skip() {
  echo "profile_test($mode): SKIP: $*"
  exit 77
}
[[ -f "$plugin" ]] || fail "plugin $plugin not found"
command -v qemu-system-arm >/dev/null 2>&1 || skip "qemu-system-arm not installed"

work="$(mktemp -d)"
trap '[[ -n "${LR_KEEP:-}" ]] || rm -rf "$work"' EXIT

# sum FILE: the sum of a profile's counts.
sum() { awk '{ s += $2 } END { print s + 0 }' "$1"; }
# profile_line OUT: the plugin's "icount: profile PATH: ..." line.
profile_line() { grep '^icount: profile ' "$1" || true; }

case "$mode" in
  image)
    # The image and its translated blocks: plugin_test.sh. TB 0x08 = {0x08, 0x0a, 0x0c} runs once,
    # TB 0x0a = {0x0a, 0x0c} 9 times, TB 0x0e = {0x0e, 0x10, 0x12} once: 0x0a and 0x0c are in
    # two TBs, whose counts the profile adds per address.
    image="$work/loop.bin"
    printf '\x00\x10\x00\x20\x09\x00\x00\x00\x0a\x22\x01\x3a\xfd\xd1\x18\x20\x00\x49\xab\xbe\x26\x00\x02\x00' >"$image"
    run_qemu() {  # run_qemu PLUGIN_ARGS: output in $work/out, profile in $work/p, status in $status
      status=0
      rm -f "$work/p"
      timeout 60 qemu-system-arm -M mps2-an386 -nographic -monitor none -semihosting \
        -kernel "$image" -d plugin -plugin "$plugin$1" </dev/null >"$work/out" 2>&1 || status=$?
    }
    expect_profile() {  # expect_profile ARGS SUMMARY LINES...: the profile and the summary line
      local args="$1" summary="$2"
      shift 2
      run_qemu ",profile=$work/p$args"
      [[ "$status" -eq 0 ]] || { cat "$work/out" >&2; fail "$args: QEMU exited with status $status"; }
      : >"$work/expected"
      [[ $# -eq 0 ]] || printf '%s\n' "$@" >"$work/expected"
      diff -u "$work/expected" "$work/p" >&2 || fail "$args: the profile differs from the expected (above)"
      [[ "$(profile_line "$work/out")" == "icount: profile $work/p: $summary" ]] \
        || { cat "$work/out" >&2; fail "$args: summary line '$(profile_line "$work/out")', expected '$summary'"; }
    }
    # No begin: from reset to exit, the whole run: the sum is the total, 24.
    expect_profile "" "1 period (the last open at exit), 24 instructions" \
      "0x8 1" "0xa 10" "0xc 10" "0xe 1" "0x10 1" "0x12 1"
    grep -qx "icount: total 24 instructions" "$work/out" || fail "the total changed with a profile"
    # Begin at the loop head (a marker too; it fires from the second iteration, at 3) to 0x0e (at
    # 21): 18 = 21 - 3, the begin TB's own instructions included; later begins inside the period
    # are ignored. The marker lines are those without a profile.
    expect_profile ",marker=0xb:loop,profile_begin=0xb,profile_end=0xe" "1 period, 18 instructions" \
      "0xa 9" "0xc 9"
    [[ "$(grep -c '^icount: marker 0xb loop at ' "$work/out")" -eq 9 ]] \
      || { cat "$work/out" >&2; fail "the marker lines changed with a profile"; }
    # The same address as begin and end: the periods alternate. The loop head fires at 3, 5, ...,
    # 19: periods [3,5) [7,9) [11,13) [15,17) and [19, exit): 4 x 2 + 5 = 13.
    expect_profile ",profile_begin=0xa,profile_end=0xa" \
      "5 periods (the last open at exit), 13 instructions" \
      "0xa 5" "0xc 5" "0xe 1" "0x10 1" "0x12 1"
    # Periods selected: skip the first, record the next two: [7,9) [11,13).
    expect_profile ",profile_begin=0xa,profile_end=0xa,profile_skip=1,profile_count=2" \
      "2 periods, 4 instructions" "0xa 2" "0xc 2"
    # An end before any begin is ignored; a begin never reached: an empty profile.
    expect_profile ",profile_begin=0x100,profile_end=0xe" "0 periods, 0 instructions"
    # A period ending at the last block: the begin block's instructions counted, the end's not.
    expect_profile ",profile_begin=0x8,profile_end=0xe" "1 period, 21 instructions" \
      "0x8 1" "0xa 10" "0xc 10"
    # Rejected arguments.
    for bad in "profile=" "profile=on" "profile_begin=0x8" "profile=$work/p,profile_begin=8" \
               "profile=$work/p,profile_end=0x8:name" "profile=$work/p,profile_skip=-1" \
               "profile=$work/p,profile_count=0" "profile=$work/p,profile_count=1x" \
               "profile=$work/no/such/dir/p"; do
      run_qemu ",$bad"
      [[ "$status" -ne 0 ]] || fail "QEMU accepted the plugin arguments '$bad'"
      grep -q '^qemu_icount: ' "$work/out" || { cat "$work/out" >&2; fail "no qemu_icount: message for '$bad'"; }
    done
    ;;

  asm)
    command -v python3 >/dev/null 2>&1 || skip "python3 not installed"
    for tool in as ld ar g++ nm addr2line; do
      command -v "arm-none-eabi-$tool" >/dev/null 2>&1 || skip "arm-none-eabi-$tool not installed"
    done
    root="$work/root"
    mkdir -p "$root/firmware/start" "$root/core/span" "$root/core/vertex" "$root/core/math" \
      "$root/hal/fake" "$work/lib"
    # The region: region_begin's bx lr (1); in reset: 5 bl (5); span_loop 1 + 5 x 2 + 1 = 12;
    # hal_poke 4; __fake_div 2 (an archive outside the tree, no line tables); vertex_sum (C++).
    cat >"$root/firmware/start/start.s" <<'EOF'
  .syntax unified
  .thumb
  .section .vectors, "a"
  .word 0x20001000
  .word reset
  .text
  .global reset
  .type reset, %function
  .thumb_func
reset:
  ldr r0, =values
  movs r1, #4
  bl region_begin
  bl span_loop
  bl hal_poke
  bl __fake_div
  bl vertex_sum
  bl region_end
  movs r0, #0x18
  ldr r1, =0x20026
  bkpt 0xab
  .size reset, . - reset
  .type region_begin, %function
  .thumb_func
region_begin:
  bx lr
  .size region_begin, . - region_begin
  .type region_end, %function
  .thumb_func
region_end:
  bx lr
  .size region_end, . - region_end
  .ltorg
values:
  .word 3, 5, 7, 11
EOF
    cat >"$root/core/span/span.s" <<'EOF'
  .syntax unified
  .thumb
  .text
  .global span_loop
  .type span_loop, %function
  .thumb_func
span_loop:
  movs r2, #5
1:
  subs r2, #1
  bne 1b
  bx lr
  .size span_loop, . - span_loop
EOF
    cat >"$root/hal/fake/hal.s" <<'EOF'
  .syntax unified
  .thumb
  .text
  .global hal_poke
  .type hal_poke, %function
  .thumb_func
hal_poke:
  nop
  nop
  nop
  bx lr
  .size hal_poke, . - hal_poke
EOF
    cat >"$work/lib/div.s" <<'EOF'
  .syntax unified
  .thumb
  .text
  .global __fake_div
  .type __fake_div, %function
  .thumb_func
__fake_div:
  movs r3, #1
  bx lr
  .size __fake_div, . - __fake_div
EOF
    cat >"$root/core/math/mix.hpp" <<'EOF'
#pragma once
// Inlined into vertex_sum (core/vertex): its instructions belong to this file by file and folder,
// to vertex_sum by function.
[[gnu::always_inline]] inline unsigned mix(unsigned x) {
  x ^= x >> 7;
  x *= 0x9e3779b1u;
  return x ^ (x >> 13);
}
EOF
    cat >"$root/core/vertex/vertex.cpp" <<'EOF'
#include "core/math/mix.hpp"
extern "C" [[gnu::noinline]] unsigned vertex_sum(const unsigned* p, int n) {
  unsigned s = 0;
  for (int i = 0; i < n; ++i) s += mix(p[i]);
  return s;
}
EOF
    cat >"$work/link.ld" <<'EOF'
SECTIONS {
  . = 0;
  .vectors : { KEEP(*(.vectors)) }
  .text : { *(.text*) }
}
EOF
    (
      cd "$work"
      for s in firmware/start/start.s core/span/span.s hal/fake/hal.s; do
        arm-none-eabi-as -mcpu=cortex-m4 -g "$root/$s" -o "$work/$(basename "$s" .s).o"
      done
      arm-none-eabi-as -mcpu=cortex-m4 lib/div.s -o lib/div.o
      arm-none-eabi-ar rcs "$work/lib/libfake.a" lib/div.o
      arm-none-eabi-g++ -mcpu=cortex-m4 -mthumb -O2 -g -ffreestanding -fno-exceptions -I "$root" \
        -c "$root/core/vertex/vertex.cpp" -o vertex.o
      arm-none-eabi-ld -T link.ld -Map "$work/t.map" start.o span.o hal.o vertex.o \
        "$work/lib/libfake.a" -o "$work/t.elf"
    ) >"$work/build.log" 2>&1 || { cat "$work/build.log" >&2; fail "building the test ELF"; }

    bash "$repo_root/scripts/icount.sh" --plugin "$plugin" --profile "$work/p" region_begin region_end \
      --machine mps2-an386 "$work/t.elf" region_begin region_end >"$work/out" 2>&1 \
      || { cat "$work/out" >&2; fail "scripts/icount.sh --profile"; }
    mapfile -t marks < <(sed -n 's/^icount: marker 0x[0-9a-f]* region_[a-z]* at \([0-9]*\)$/\1/p' "$work/out")
    [[ "${#marks[@]}" -eq 2 ]] || { cat "$work/out" >&2; fail "expected 2 marker lines"; }
    region=$((marks[1] - marks[0]))
    [[ "$(sum "$work/p")" -eq "$region" ]] || fail "the profile sums to $(sum "$work/p"), the markers differ by $region"

    table() {  # table BY: "NAME COUNT" lines of the script's --tsv output, sorted
      python3 "$profile_py" --root "$root" "$work/t.elf" "$work/p" --by "$1" --tsv \
        | awk -F '\t' '{ print $1 " " $2 }' | LC_ALL=C sort
    }
    table function >"$work/function"
    vertex="$(awk '$1 == "vertex_sum" { print $2 }' "$work/function")"
    [[ -n "$vertex" && "$vertex" -gt 0 ]] || { cat "$work/function" >&2; fail "no vertex_sum row"; }
    [[ "$region" -eq $((1 + 5 + 12 + 4 + 2 + vertex)) ]] \
      || fail "the region is $region instructions, expected $((1 + 5 + 12 + 4 + 2)) + vertex_sum's $vertex"
    printf '%s\n' "__fake_div 2" "hal_poke 4" "region_begin 1" "reset 5" "span_loop 12" \
      "vertex_sum $vertex" | LC_ALL=C sort >"$work/expected"
    diff -u "$work/expected" "$work/function" >&2 || fail "--by function differs from the expected (above)"

    # By file and folder: mix()'s inlined instructions go to core/math, the rest of vertex_sum to
    # core/vertex; together they are vertex_sum's count.
    table folder >"$work/folder"
    math="$(awk '$1 == "core/math" { print $2 }' "$work/folder")"
    [[ -n "$math" && "$math" -gt 0 && "$math" -lt "$vertex" ]] \
      || { cat "$work/folder" >&2; fail "mix()'s inlined code is not a core/math row"; }
    printf '%s\n' "core/math $math" "core/span 12" "core/vertex $((vertex - math))" \
      "firmware/start 6" "hal/fake 4" "libfake: __fake_div 2" | LC_ALL=C sort >"$work/expected"
    diff -u "$work/expected" "$work/folder" >&2 || fail "--by folder differs from the expected (above)"
    table file >"$work/file"
    printf '%s\n' "core/math/mix.hpp $math" "core/span/span.s 12" \
      "core/vertex/vertex.cpp $((vertex - math))" "firmware/start/start.s 6" "hal/fake/hal.s 4" \
      "libfake: __fake_div 2" | LC_ALL=C sort >"$work/expected"
    diff -u "$work/expected" "$work/file" >&2 || fail "--by file differs from the expected (above)"
    ;;

  firmware)
    [[ $# -eq 3 ]] || fail "firmware needs the ELF"
    elf="$3"
    [[ -f "$elf" ]] || skip "$elf not built (cmake --preset cortex-m4f && cmake --build --preset cortex-m4f -j2)"
    command -v python3 >/dev/null 2>&1 || skip "python3 not installed"
    command -v arm-none-eabi-nm >/dev/null 2>&1 || skip "arm-none-eabi-nm not installed"
    machine=mps2-an386
    [[ -f "${elf%.elf}.machine" ]] && machine="$(tr -d '[:space:]' <"${elf%.elf}.machine")"
    run_icount() {  # run_icount OUT [icount.sh options]: profile to $work/p, output to OUT
      local out="$1"
      shift
      bash "$repo_root/scripts/icount.sh" --plugin "$plugin" --profile "$work/p" lr_icount_begin \
        lr_icount_end "$@" --machine "$machine" "$elf" lr_icount_begin lr_icount_end >"$out" 2>&1 \
        || { cat "$out" >&2; fail "scripts/icount.sh --profile $*"; }
    }
    run_icount "$work/out"
    # The periods as the plugin defines them (a begin outside a period starts one, an end inside
    # one ends it) from the marker lines; and the firmware's expected counts of those cases (every
    # case but begin_body, whose begin marker is lr_icount_begin4).
    read -r periods differences expected < <(awk '
      /^icount: marker 0x[0-9a-f]+ lr_icount_begin at / { if (!open) { open = 1; b = $6 } }
      /^icount: marker 0x[0-9a-f]+ lr_icount_end at / { if (open) { open = 0; d += $6 - b; ++p } }
      /^icount_check: case [^ ]+ expected / { if ($3 != "begin_body") e += $5 }
      END { print p, d, e }' "$work/out")
    [[ "$periods" -gt 0 ]] || fail "no begin/end periods in the output"
    [[ "$(sum "$work/p")" -eq "$differences" ]] \
      || fail "the profile sums to $(sum "$work/p"), the $periods periods' marker differences to $differences"
    [[ "$differences" -eq "$expected" ]] || fail "the marker differences sum to $differences, the firmware expects $expected"
    [[ "$(profile_line "$work/out")" == "icount: profile $work/p: $periods periods, $differences instructions" ]] \
      || fail "summary line: $(profile_line "$work/out")"

    # The loop case: 1000 iterations of 4 instructions in case_loop, plus its bl to the end marker;
    # the begin marker's bx lr once per period.
    python3 "$profile_py" "$elf" "$work/p" --by function --tsv >"$work/function"
    row() { awk -F '\t' -v n="$1" '$1 == n { print $2 }' "$work/function"; }
    [[ "$(row "(anonymous namespace)::case_loop")" == 4001 ]] \
      || { cat "$work/function" >&2; fail "case_loop: $(row "(anonymous namespace)::case_loop"), expected 4001"; }
    [[ "$(row lr_icount_begin)" == "$periods" ]] || fail "lr_icount_begin: $(row lr_icount_begin), expected $periods"
    read -r start size < <(arm-none-eabi-nm -S -C "$elf" \
      | awk '$4 == "(anonymous" && $5 == "namespace)::case_loop()" { print $1, $2 }')
    [[ -n "$start" ]] || fail "no case_loop symbol"
    in_loop="$(python3 -c '
import sys
start, end = int(sys.argv[1], 16), int(sys.argv[1], 16) + int(sys.argv[2], 16)
for line in open(sys.argv[3]):
    address, count = line.split()
    if start <= int(address, 16) < end:
        print(count, end=" ")' "$start" "$size" "$work/p")"
    [[ "$in_loop" == "1000 1000 1000 1000 1 " ]] \
      || fail "case_loop's addresses count '$in_loop', expected the loop's 4 x 1000 and the bl's 1"

    # One period: the loop case's (its index among the periods' cases), alone.
    index="$(awk '/^icount_check: case / && $3 != "begin_body" { if ($3 == "loop") { print n; exit } ++n }' "$work/out")"
    [[ -n "$index" ]] || fail "no loop case in the output"
    run_icount "$work/out1" --profile-skip "$index" --profile-count 1
    [[ "$(sum "$work/p")" -eq 4002 ]] || fail "the loop case's period sums to $(sum "$work/p"), expected 4002"
    [[ "$(profile_line "$work/out1")" == "icount: profile $work/p: 1 period, 4002 instructions" ]] \
      || fail "summary line: $(profile_line "$work/out1")"
    ;;
  *) fail "unknown mode $mode" ;;
esac
echo "profile_test($mode): PASS"
