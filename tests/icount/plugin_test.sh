#!/usr/bin/env bash
# Tests of the instruction-counting plugin (tools/qemu_icount) that need only qemu-system-arm, no
# cross compiler: the guest is a 24-byte image assembled by hand below.
#
# Usage: tests/icount/plugin_test.sh PLUGIN_SO counts|arguments|exports
#   counts     exact marker lines and total for the hand-assembled image
#   arguments  malformed plugin arguments make QEMU fail with the plugin's message
#   exports    the library exports only qemu_plugin_install and qemu_plugin_version
# Exit status: 0 pass, 1 fail, 77 skip (qemu-system-arm or nm missing).
set -euo pipefail

[[ $# -eq 2 ]] || { echo "usage: $0 PLUGIN_SO counts|arguments|exports" >&2; exit 1; }
plugin="$1"
mode="$2"
fail() {
  echo "plugin_test($mode): FAIL: $*" >&2
  exit 1
}
[[ -f "$plugin" ]] || fail "plugin $plugin not found"
command -v qemu-system-arm >/dev/null 2>&1 || { echo "plugin_test: SKIP: qemu-system-arm not installed"; exit 77; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# The image, loaded at 0 by qemu-system-arm -M mps2-an386 -kernel (a raw image: not an ELF).
# Thumb encodings, little-endian halfwords:
#   0x00  .word 0x20001000      initial SP
#   0x04  .word 0x00000009      reset vector: 0x08, Thumb
#   0x08  movs r2, #10          220a
#   0x0a  subs r2, #1           3a01   <- loop head
#   0x0c  bne  0x0a             d1fd   (offset -6: imm8 = 0xfd)
#   0x0e  movs r0, #0x18        2018   SYS_EXIT
#   0x10  ldr  r1, [pc, #0]     4900   loads the word at 0x14
#   0x12  bkpt 0xab             beab   semihosting call
#   0x14  .word 0x00020026      ADP_Stopped_ApplicationExit (QEMU exits with status 0)
# QEMU translates a block at 0x08 (movs, subs, bne: 3 instructions), one at 0x0a (subs, bne: 2)
# for the 9 further iterations, and one at 0x0e (movs, ldr, bkpt: 3). Executed: 1 + 10 x 2 + 3 = 24.
# A marker line shows the count before the marker's block: 0x08 at 0; 0x0a at 3, 5, ..., 19 (not
# on the first iteration: 0x0a is then inside the block that starts at 0x08); 0x0e at 21.
image="$work/loop.bin"
printf '\x00\x10\x00\x20\x09\x00\x00\x00\x0a\x22\x01\x3a\xfd\xd1\x18\x20\x00\x49\xab\xbe\x26\x00\x02\x00' >"$image"
[[ "$(wc -c <"$image")" -eq 24 ]] || fail "the test image is $(wc -c <"$image") bytes, not 24"

run_qemu() {  # run_qemu PLUGIN_ARGS: QEMU's output (stdout + stderr) in $work/out, status in $status
  status=0
  timeout 60 qemu-system-arm -M mps2-an386 -nographic -monitor none -semihosting -kernel "$image" \
    -d plugin -plugin "$plugin$1" </dev/null >"$work/out" 2>&1 || status=$?
}

case "$mode" in
  counts)
    # 0xb: the Thumb bit is ignored. 0x100: never reached.
    run_qemu ",marker=0x8:reset,marker=0xb:loop,marker=0xe,marker=0x100:nowhere"
    [[ "$status" -eq 0 ]] || { cat "$work/out" >&2; fail "QEMU exited with status $status"; }
    {
      echo "icount: marker 0x8 reset at 0"
      for n in 3 5 7 9 11 13 15 17 19; do echo "icount: marker 0xb loop at $n"; done
      echo "icount: marker 0xe at 21"
      echo "icount: marker 0x100 nowhere never executed"
      echo "icount: total 24 instructions"
    } >"$work/expected"
    diff -u "$work/expected" "$work/out" >&2 || fail "QEMU's output differs from the expected lines (above)"
    # Without markers: only the total.
    run_qemu ""
    [[ "$status" -eq 0 && "$(cat "$work/out")" == "icount: total 24 instructions" ]] \
      || { cat "$work/out" >&2; fail "without markers: expected only the total (status $status)"; }
    ;;
  arguments)
    for bad in "marker=1234" "marker=0x" "marker=0xg1" "marker=0x12z" "marker=-0x1" "count=1" \
               "marker=0x8,marker=0x9" "marker=0x100000000000000000"; do
      run_qemu ",$bad"
      [[ "$status" -ne 0 ]] || fail "QEMU accepted the plugin argument '$bad'"
      grep -q '^qemu_icount: ' "$work/out" || { cat "$work/out" >&2; fail "no qemu_icount: message for '$bad'"; }
    done
    # A machine with more than one vCPU: the counter is not atomic.
    status=0
    timeout 60 qemu-system-arm -M virt -smp 2 -nographic -monitor none -d plugin -plugin "$plugin" \
      </dev/null >"$work/out" 2>&1 || status=$?
    if [[ "$status" -eq 0 ]] || ! grep -q '^qemu_icount: needs exactly one vCPU' "$work/out"; then
      cat "$work/out" >&2
      fail "two vCPUs were not refused (status $status)"
    fi
    ;;
  exports)
    command -v nm >/dev/null 2>&1 || { echo "plugin_test: SKIP: nm not installed"; exit 77; }
    exported="$(nm -D --defined-only "$plugin" | awk '$2 ~ /^[A-Z]$/ { print $3 }' | sort | tr '\n' ' ')"
    [[ "$exported" == "qemu_plugin_install qemu_plugin_version " ]] \
      || fail "exported symbols: '$exported' (expected qemu_plugin_install and qemu_plugin_version only)"
    ;;
  *) fail "unknown mode $mode" ;;
esac
echo "plugin_test($mode): PASS"
