#!/usr/bin/env bash
# Cross-compile check of every Cortex-M target. For each preset (cortex-m0plus, cortex-m4f,
# cortex-m7, cortex-m33: toolchain/cortex-*.cmake, LR_HOST=OFF), one configure and one build into
# build/<preset>, then:
#   - the link guard: no ELF of the build tree may hold a heap, exception machinery or floating
#     point (the rules: scripts/lib/firmware_rules.sh);
#   - with LR_CROSS_RUN_QEMU=1, under qemu-system-arm with semihosting, each run bounded by
#     `timeout` (a hung firmware never stops QEMU by itself):
#       lr_smoke on the preset's board (LR_FW_BOARD; board names are QEMU machine names,
#       firmware/boards.cmake): must pass, and its frame checksum must equal the host build's
#       when LR_HOST_SMOKE is given;
#       lr_span_check on its board (firmware/span_check: the lanes row loop by hand against its
#       C twin, and the C twin against the generic row loop) and lr_bin_check (firmware/bin_check:
#       the front end's bin lane by hand against its C twin): must pass. The Cortex-M0+ image also runs on mps2-an385 (the M3 that
#       runs the M0+ images needing more than the micro:bit's 16 KB; same ELF, same frame);
#       the fault checks (firmware/fault_check, listed in its fault_checks.txt): each must end
#       QEMU with a failure status and report "HardFault: pc=" the address of lr_fault_trigger.
# Ends with one summary line per board (and per preset).
#
# Usage: scripts/ci_cross.sh            (from any directory)
#   LR_CROSS_RUN_QEMU=1 scripts/ci_cross.sh   also runs the images under QEMU (see above)
#   LR_HOST_SMOKE=path/to/lr_smoke_host        the smoke firmware built for the host
#                                             (tests/firmware_host): the checksums must match
#   LR_CROSS_PRESETS="cortex-m4f cortex-m7"    a subset of the presets (default: all four)
#   LR_CROSS_QEMU_TIMEOUT=seconds              limit of one QEMU run (default 60)
#   LR_HOST_TOOLS_DIR=build/debug              a host tree that has built lineraster-asset
# Extra compiler flags: CXXFLAGS in the environment (read at the first configure of a build
# tree; see toolchain/cortex-m4f.cmake). Never -DCMAKE_CXX_FLAGS.
# Exit status: 0 on success, 1 on any failure (with a message saying which).
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

read -r -a presets <<<"${LR_CROSS_PRESETS:-cortex-m0plus cortex-m4f cortex-m7 cortex-m33}"
qemu_timeout="${LR_CROSS_QEMU_TIMEOUT:-60}"
run_qemu="${LR_CROSS_RUN_QEMU:-0}"
jobs="$(nproc)"

fail() {
  echo "ci_cross: FAIL: $*" >&2
  exit 1
}

# Failures of one preset or board are counted and reported, and the others still run.
failures=0
problem() {
  echo "ci_cross: FAIL: $*" >&2
  failures=$((failures + 1))
}

for tool in arm-none-eabi-g++ arm-none-eabi-gcc arm-none-eabi-nm arm-none-eabi-objdump arm-none-eabi-readelf arm-none-eabi-size; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    fail "$tool not found on PATH. Install the Arm GNU toolchain (Debian/Ubuntu: gcc-arm-none-eabi," \
      "libnewlib-arm-none-eabi, libstdc++-arm-none-eabi-newlib; the project's setup script does this)."
  fi
done
command -v cmake >/dev/null 2>&1 || fail "cmake not found on PATH"
if [[ "$run_qemu" == 1 ]]; then
  command -v qemu-system-arm >/dev/null 2>&1 || fail "LR_CROSS_RUN_QEMU=1 but qemu-system-arm is not installed"
  command -v timeout >/dev/null 2>&1 || fail "timeout (coreutils) not found on PATH"
fi

echo "ci_cross: $(arm-none-eabi-g++ --version | head -n 1)"

# The host's frame, once: the same main.cpp built for the PC (tests/firmware_host).
host_sum=""
if [[ "$run_qemu" == 1 && -n "${LR_HOST_SMOKE:-}" ]]; then
  host_out="$("$LR_HOST_SMOKE")" || fail "the host build of the smoke firmware ($LR_HOST_SMOKE) failed: $host_out"
  host_sum="$(grep -o 'checksum.*' <<<"$host_out" || true)"
  [[ -n "$host_sum" ]] || fail "no checksum line in the output of $LR_HOST_SMOKE"
  echo "ci_cross: host frame: $host_sum"
fi

# The link guard's rules (heap, exceptions, floating point): scripts/lib/firmware_rules.sh.
# shellcheck source=scripts/lib/firmware_rules.sh
source "$repo_root/scripts/lib/firmware_rules.sh"

# link_guard ELF: 0 if the ELF breaks none of the rules; else prints what it holds.
link_guard() {
  local elf="$1" found
  found="$(lr_fw_guard "$elf")" && return 0
  echo "ci_cross: $elf breaks the firmware rules (the map file's --cref section says who references a symbol):" >&2
  sed 's/^/    /' <<<"$found" >&2
  return 1
}

indent() { sed 's/^/    /'; }

# qemu MACHINE ELF: runs the ELF; sets qemu_out (semihosting output arrives on QEMU's stderr) and
# qemu_status (124: timed out).
qemu() {
  local machine="$1" elf="$2"
  qemu_status=0
  qemu_out="$(timeout -k 5 "$qemu_timeout" qemu-system-arm -M "$machine" -nographic -monitor none \
    -semihosting -kernel "$elf" 2>&1)" || qemu_status=$?
}

# smoke PRESET MACHINE ELF: runs lr_smoke; on success sets smoke_note, else reports a problem.
smoke() {
  local preset="$1" machine="$2" elf="$3" sum stack
  echo "ci_cross: [$preset] lr_smoke on $machine"
  qemu "$machine" "$elf"
  indent <<<"$qemu_out"
  if [[ $qemu_status == 124 ]]; then
    problem "[$preset] lr_smoke on $machine did not finish within ${qemu_timeout} s (hung, or a fault with semihosting off)"
    return 1
  fi
  if [[ $qemu_status != 0 ]] || ! grep -q '^lr_smoke: PASS' <<<"$qemu_out"; then
    problem "[$preset] lr_smoke failed on $machine (QEMU status $qemu_status)"
    return 1
  fi
  sum="$(grep -o 'checksum.*' <<<"$qemu_out" || true)"
  if [[ -n "$host_sum" && "$sum" != "$host_sum" ]]; then
    problem "[$preset] frame on $machine differs from the host's ($sum; host: $host_sum)"
    return 1
  fi
  stack="$(sed -n 's/^ *stack used (bytes): //p' <<<"$qemu_out")"
  smoke_note="lr_smoke ${sum##* }${host_sum:+ == host}, stack ${stack:-?} B"
}

# span_check PRESET BUILD_DIR [IMAGE]: runs IMAGE (default lr_span_check; lr_bin_check) on its
# board (images.txt); adds to span_note.
span_check() {
  local preset="$1" build_dir="$2" image="${3:-lr_span_check}" name board machine elf
  read -r name board machine elf < <(grep "^$image " "$build_dir/firmware/images.txt" || true)
  if [[ -z "${elf:-}" || ! -f "$elf" ]]; then
    problem "[$preset] $image not built"
    return 1
  fi
  echo "ci_cross: [$preset] $image on $machine"
  qemu "$machine" "$elf"
  indent <<<"$qemu_out"
  if [[ $qemu_status != 0 ]] || ! grep -q "^$image: PASS" <<<"$qemu_out"; then
    problem "[$preset] $image failed on $machine (QEMU status $qemu_status)"
    return 1
  fi
  span_note="${span_note:+$span_note, }$image on $machine"
}

# faults PRESET MACHINE LIST: runs the fault checks of LIST for MACHINE; sets fault_note.
faults() {
  local preset="$1" machine="$2" list="$3" m elf trigger expected passed=0 total=0
  while read -r m elf; do
    [[ "$m" == "$machine" ]] || continue
    total=$((total + 1))
    trigger="$(arm-none-eabi-nm "$elf" | awk '$3 == "lr_fault_trigger" {print $1}')"
    expected="HardFault: pc=0x$(printf '%08x' "$((16#${trigger:-0} & ~1))")"
    qemu "$machine" "$elf"
    if [[ $qemu_status == 124 ]]; then
      problem "[$preset] $(basename "$elf") on $machine did not finish within ${qemu_timeout} s: the fault handler did not end the run"
    elif [[ $qemu_status == 0 ]]; then
      problem "[$preset] $(basename "$elf") on $machine exited with status 0: a fault must end the run with a failure"
    elif [[ -z "$trigger" ]] || ! grep -q "^$expected " <<<"$qemu_out"; then
      problem "[$preset] $(basename "$elf") on $machine: no \"$expected ...\" line (the handler missed the fault or its frame)"
    else
      passed=$((passed + 1))
      echo "ci_cross: [$preset] $(basename "$elf") on $machine: $(grep '^HardFault' <<<"$qemu_out"), status $qemu_status"
      continue
    fi
    indent <<<"$qemu_out"
  done <"$list"
  fault_note="fault checks $passed/$total"
  [[ $passed == "$total" ]]
}

summary=()
for preset in "${presets[@]}"; do
  build_dir="build/$preset"
  echo "ci_cross: configuring preset $preset"
  # LR_HOST_TOOLS_DIR (environment): a host build tree with lineraster-asset, instead of building
  # it once more in build/host-tools (firmware/host_tools.cmake).
  if ! cmake --preset "$preset" ${LR_HOST_TOOLS_DIR:+"-DLR_HOST_TOOLS_DIR=$LR_HOST_TOOLS_DIR"}; then
    problem "configure of preset $preset failed"
    summary+=("FAIL  $preset: configure failed")
    continue
  fi
  board="$(sed -n 's/^LR_FW_BOARD:[A-Z]*=//p' "$build_dir/CMakeCache.txt")"
  smoke_elf="$build_dir/firmware/lr_smoke.elf"
  fault_list="$build_dir/firmware/fault_check/fault_checks.txt"

  echo "ci_cross: building preset $preset"
  # -k (the presets use Unix Makefiles): on an error, make still builds every target that does
  # not depend on the broken one.
  if ! cmake --build --preset "$preset" --parallel "$jobs" -- -k; then
    problem "build of preset $preset failed (see the compiler output above)"
    summary+=("FAIL  $preset: build failed (see above)")
    # The images this script runs may still be fine: check them if they are up to date (a
    # stale ELF from an earlier build must not pass for a new one).
    checked=(lr_smoke)
    [[ -f "$fault_list" ]] && mapfile -t -O 1 checked < <(awk '{n = $2; sub(/.*\//, "", n); sub(/\.elf$/, "", n); print n}' "$fault_list")
    if ! cmake --build --preset "$preset" --target "${checked[@]}" >/dev/null 2>&1; then
      summary+=("FAIL  $preset on $board: lr_smoke or a fault check does not build")
      continue
    fi
    echo "ci_cross: [$preset] ${checked[*]} are built and up to date: checking them anyway"
  fi
  [[ -f "$smoke_elf" ]] || { problem "[$preset] expected firmware ELF not found: $smoke_elf"; continue; }

  mapfile -t elfs < <(find "$build_dir" -name '*.elf' -type f | sort)
  guard_ok=0
  for elf in "${elfs[@]}"; do
    if link_guard "$elf"; then guard_ok=$((guard_ok + 1)); else problem "[$preset] $elf fails the link guard"; fi
  done
  echo "ci_cross: [$preset] link guard ($lr_fw_guard_what): $guard_ok of ${#elfs[@]} ELFs clean"
  read -r text data bss _ < <(arm-none-eabi-size "$smoke_elf" | tail -n 1)
  sizes="lr_smoke text $text data $data bss $bss"

  if [[ "$run_qemu" != 1 ]]; then
    verdict=PASS
    [[ $guard_ok == "${#elfs[@]}" ]] || verdict=FAIL
    summary+=("$verdict  $preset on $board: built, link guard $guard_ok/${#elfs[@]} ELFs; $sizes")
    continue
  fi

  # Boards this preset's images run on: its own, and those the fault checks name.
  machines=("$board")
  if [[ -f "$fault_list" ]]; then
    while read -r m _; do [[ " ${machines[*]} " == *" $m "* ]] || machines+=("$m"); done <"$fault_list"
  fi
  for machine in "${machines[@]}"; do
    line="$preset on $machine:"
    smoke_note="" fault_note="no fault check"
    ok=1
    # The M0+ smoke image (linked for the micro:bit) also runs on the M3 of mps2-an385: its
    # memory map holds the micro:bit's (flash at 0, RAM at 0x20000000).
    if [[ "$machine" == "$board" || ("$preset" == cortex-m0plus && "$machine" == mps2-an385) ]]; then
      smoke "$preset" "$machine" "$smoke_elf" || ok=0
    fi
    span_note=""
    if [[ "$machine" == "$board" ]]; then
      span_check "$preset" "$build_dir" || ok=0
      span_check "$preset" "$build_dir" lr_bin_check || ok=0
    fi
    if [[ -f "$fault_list" ]]; then
      faults "$preset" "$machine" "$fault_list" || ok=0
    else
      problem "[$preset] $fault_list not found (firmware/fault_check not built?)"
      ok=0
    fi
    [[ "$machine" == "$board" ]] && line+=" $sizes;"
    line+="${smoke_note:+ $smoke_note;}${span_note:+ $span_note;} $fault_note"
    if [[ $ok == 1 ]]; then summary+=("PASS  $line"); else summary+=("FAIL  $line"); fi
  done
done

echo "ci_cross: summary"
printf '  %s\n' "${summary[@]}"
if [[ $failures != 0 ]]; then
  fail "$failures check(s) failed (messages above)"
fi
echo "ci_cross: PASS"
