#!/usr/bin/env bash
# The demo firmware on every bare-metal build tree: runs each lr_demo_* image under QEMU on its
# board (semihosting writes the frame to a PPM file), renders the same scene with lineraster-sim
# on this machine (the arguments after "sim:" in the scene's header, firmware/demo/*_scene.hpp)
# and compares the two files byte for byte.
#
# Usage: scripts/ci_firmware.sh [build tree ...]   (default: every build/cortex-* with images)
#   LR_SIM=path/to/lineraster-sim   (default: build/debug/host_sim/lineraster-sim)
# Frames go to out/firmware/<tree>/ (QEMU's working directory for the run).
# Exit status: 0 when every frame is identical to the host's, 1 otherwise (with the reason).
set -euo pipefail
repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

sim="${LR_SIM:-build/debug/host_sim/lineraster-sim}"
timeout_s="${LR_QEMU_TIMEOUT:-300}"
fail() {
  echo "ci_firmware: FAIL: $*" >&2
  exit 1
}
[[ -x "$sim" ]] || fail "$sim not built (cmake --preset debug && cmake --build --preset debug --target lineraster-sim)"
# The stack analysis's rules for calls through pointers: scripts/lib/firmware_rules.sh.
# shellcheck source=scripts/lib/firmware_rules.sh
source scripts/lib/firmware_rules.sh
command -v qemu-system-arm >/dev/null 2>&1 || fail "qemu-system-arm not installed (scripts/setup.sh test)"

trees=("$@")
if [[ ${#trees[@]} -eq 0 ]]; then
  for t in build/cortex-*; do [[ -f "$t/firmware/images.txt" ]] && trees+=("$t"); done
fi
[[ ${#trees[@]} -gt 0 ]] || fail "no bare-metal build tree with firmware/images.txt (run scripts/ci_cross.sh first)"

checked=0
for tree in "${trees[@]}"; do
  list="$tree/firmware/images.txt"
  [[ -f "$list" ]] || fail "$list missing (configure and build $tree first)"
  out="out/firmware/$(basename "$tree")"
  mkdir -p "$out"
  while read -r name board machine elf; do
    [[ "$name" == lr_demo_* ]] || continue
    [[ -f "$elf" ]] || fail "$elf not built"
    scene="${name#lr_demo_}"
    header="firmware/demo/${scene}_scene.hpp"
    sim_args="$(sed -n 's|^// sim: ||p' "$header")"
    [[ -n "$sim_args" ]] || fail "$header has no '// sim: ...' line"
    rm -f "$out/$name.ppm"
    # QEMU never returns if the firmware hangs: the timeout is a failure. A fault ends the run
    # through semihosting with status 1 (firmware/common/startup.cpp).
    set +e
    log="$(cd "$out" && timeout "$timeout_s" qemu-system-arm -M "$machine" -nographic -monitor none \
      -semihosting -kernel "$elf" 2>&1)"
    rc=$?
    set -e
    [[ $rc -eq 124 ]] && fail "$name ($board) did not finish within ${timeout_s} s under QEMU"
    [[ $rc -eq 0 ]] || { echo "$log" >&2; fail "$name ($board) exited with status $rc"; }
    [[ -f "$out/$name.ppm" ]] || fail "$name ($board) wrote no $out/$name.ppm"
    # A firmware that sends its frame through a panel (the Cortex-M7 demo: firmware/demo/output.hpp)
    # names the emulated panel whose image its file must equal.
    extra="$(sed -n 's/^lr_demo: sim options: //p' <<<"$log")"
    sim_args+=" $extra"
    # shellcheck disable=SC2086  # sim_args is a list of arguments
    "$sim" $sim_args --out "$out/sim_$scene.ppm" >/dev/null || fail "lineraster-sim $sim_args failed"
    if ! cmp -s "$out/$name.ppm" "$out/sim_$scene.ppm"; then
      fail "$name on $board: frame differs from lineraster-sim's ($(cmp "$out/$name.ppm" "$out/sim_$scene.ppm" | head -1))"
    fi
    # The stack the linker script reserves must cover the static worst case (scripts/stack_usage.py).
    reserved="$(arm-none-eabi-nm "$elf" | awk '$NF == "__stack_size" { print $1 }')"
    [[ -n "$reserved" ]] && reserved=$((16#$reserved))
    worst="$(python3 scripts/stack_usage.py "$elf" "$tree" --vector-table .isr_vector --entry main \
      "${lr_fw_stack_rules[@]}" --tool-prefix arm-none-eabi- --machine 2>&1)" \
      || fail "$name ($board): stack analysis failed: $worst"
    worst="$(awk -F'\t' '$1 == "total" { print $2 }' <<<"$worst")"
    [[ -n "$reserved" && -n "$worst" ]] || fail "$name ($board): no __stack_size symbol or no stack total"
    ((worst <= reserved)) || fail "$name ($board): worst-case stack $worst B > the $reserved B the linker script reserves"
    sum="$(grep -o 'checksum.*' <<<"$log" | awk '{print $NF}')"
    pixels="$(grep -o 'pixels written: [0-9]*' <<<"$log" | awk '{print $NF}')"
    via="$(sed -n 's/^lr_demo: DMA: /; DMA: /p' <<<"$log")"
    echo "ci_firmware: $name on $board ($machine): frame identical to lineraster-sim's${extra:+ ($extra)} ($pixels pixels written, FNV-1a $sum$via); stack: worst case $worst B of $reserved B reserved"
    checked=$((checked + 1))
  done <"$list"
done
[[ $checked -gt 0 ]] || fail "no lr_demo_* image found in ${trees[*]}"
echo "ci_firmware: PASS ($checked frames)"
