#!/usr/bin/env bash
# Runs a bare-metal ELF under qemu-system-arm with the instruction-counting plugin
# (tools/qemu_icount) and prints, as the program runs, one line each time the guest enters a
# marker function, with the exact number of guest instructions executed before it:
#
#   icount: marker 0x401 lr_icount_begin at 1234
#   ...the firmware's semihosting output...
#   icount: total 5678 instructions
#
# The difference between two marker lines counts the instructions from the first marker's first
# instruction (included) to the second marker's first instruction (excluded). Measured regions
# must contain no semihosting call, fault or interrupt (tools/qemu_icount/README.md says why).
#
# Usage: scripts/icount.sh [--plugin SO] [--profile OUT BEGIN_SYMBOL END_SYMBOL
#                          [--profile-skip K] [--profile-count N]] --machine M ELF [MARKER_SYMBOL...]
#   --profile OUT BEGIN_SYMBOL END_SYMBOL
#                 also write OUT: "0xADDR COUNT" per instruction address, how often it executed
#                 between BEGIN_SYMBOL's entry (included) and END_SYMBOL's (excluded), summed
#                 over every such period (the same symbol twice: every other entry begins one);
#                 scripts/icount_profile.py ELF OUT attributes it to functions, files, folders.
#                 At least one MARKER_SYMBOL is required only without --profile.
#   --profile-skip K   leave the first K periods out of the profile (default 0)
#   --profile-count N  record N periods after those (default: all)
#   --plugin SO   the plugin (default: $LR_ICOUNT_PLUGIN, else
#                 build/release/tools/qemu_icount/libqemu_icount.so if built
#                 (`cmake --build --preset release --target lr_qemu_icount`), else the debug
#                 build's)
#   --machine M   QEMU's machine (mps2-an386 for Cortex-M4F images, microbit for Cortex-M0+, ...)
#   MARKER_SYMBOL function symbols of ELF (arm-none-eabi-nm names, e.g. lr_icount_begin); their
#                 addresses are resolved here and passed to the plugin
# Environment: LR_ICOUNT_TIMEOUT seconds QEMU may run (default 600).
# Output: QEMU's stdout and stderr (the plugin's lines and the semihosting output) on stdout.
# Exit status: 0 when QEMU exits with 0 (the firmware's semihosting exit status); 1 on a usage or
# setup error, a timeout, a QEMU error or a firmware failure, with a one-line error on stderr.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

fail() {
  echo "icount: error: $*" >&2
  exit 1
}
usage() {
  echo "usage: scripts/icount.sh [--plugin SO] [--profile OUT BEGIN_SYMBOL END_SYMBOL [--profile-skip K] [--profile-count N]] --machine M ELF [MARKER_SYMBOL...]" >&2
  exit 1
}

# Default: the release build's plugin, else the debug build's (scripts/test.sh builds that one).
plugin="${LR_ICOUNT_PLUGIN:-$repo_root/build/release/tools/qemu_icount/libqemu_icount.so}"
if [[ -z "${LR_ICOUNT_PLUGIN:-}" && ! -f "$plugin" ]]; then
  plugin="$repo_root/build/debug/tools/qemu_icount/libqemu_icount.so"
fi
machine=""
profile_out=""
profile_begin=""
profile_end=""
profile_skip=""
profile_count=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --plugin) [[ $# -ge 2 ]] || usage; plugin="$2"; shift 2 ;;
    --machine) [[ $# -ge 2 ]] || usage; machine="$2"; shift 2 ;;
    --profile) [[ $# -ge 4 ]] || usage; profile_out="$2"; profile_begin="$3"; profile_end="$4"; shift 4 ;;
    --profile-skip) [[ $# -ge 2 && "$2" =~ ^[0-9]+$ ]] || usage; profile_skip="$2"; shift 2 ;;
    --profile-count) [[ $# -ge 2 && "$2" =~ ^[1-9][0-9]*$ ]] || usage; profile_count="$2"; shift 2 ;;
    -h|--help) sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    --) shift; break ;;
    -*) echo "icount: unknown option $1" >&2; usage ;;
    *) break ;;
  esac
done
[[ -n "$machine" ]] || { echo "icount: --machine is required" >&2; usage; }
if [[ -n "$profile_out" ]]; then
  [[ $# -ge 1 ]] || usage
else
  [[ $# -ge 2 ]] || usage
  [[ -z "$profile_skip$profile_count" ]] || { echo "icount: --profile-skip/--profile-count need --profile" >&2; usage; }
fi
elf="$1"
shift
timeout_s="${LR_ICOUNT_TIMEOUT:-600}"
[[ "$timeout_s" =~ ^[1-9][0-9]*$ ]] || fail "LR_ICOUNT_TIMEOUT must be a positive number of seconds, not '$timeout_s'"

command -v qemu-system-arm >/dev/null 2>&1 || fail "qemu-system-arm not found on PATH (Debian: apt-get install qemu-system-arm)"
command -v arm-none-eabi-nm >/dev/null 2>&1 || fail "arm-none-eabi-nm not found on PATH (Debian: apt-get install binutils-arm-none-eabi)"
[[ -f "$plugin" ]] || fail "plugin $plugin not found (cmake --preset release && cmake --build --preset release --target lr_qemu_icount, or --plugin / LR_ICOUNT_PLUGIN)"
[[ -f "$elf" ]] || fail "ELF $elf not found"

symbols="$(arm-none-eabi-nm "$elf" 2>&1)" || fail "arm-none-eabi-nm cannot read $elf: $(head -n 1 <<<"$symbols")"

# address_of SYMBOL: the function symbol's address (hexadecimal, no 0x), or fail.
address_of() {
  local sym="$1" addrs
  [[ "$sym" =~ ^[A-Za-z_.$][A-Za-z0-9_.$]*$ ]] || fail "'$sym' is not a plain symbol name (give the name arm-none-eabi-nm prints)"
  # nm lines: "ADDRESS TYPE NAME"; a function is T/t (W/w when weak).
  addrs="$(awk -v s="$sym" '$3 == s && $2 ~ /^[TtWw]$/ { print $1 }' <<<"$symbols")"
  [[ -n "$addrs" ]] || fail "no function symbol '$sym' in $elf (arm-none-eabi-nm $elf | grep $sym)"
  [[ "$(wc -l <<<"$addrs")" -eq 1 ]] || fail "symbol '$sym' is defined more than once in $elf"
  echo "$addrs"
}

# QEMU's -plugin value: FILE,marker=0xADDR:NAME,... (the plugin prints NAME with the address).
# QEMU splits it at commas: the profile's path may not contain one.
plugin_arg="$plugin"
if [[ -n "$profile_out" ]]; then
  [[ "$profile_out" != *,* ]] || fail "the profile's path '$profile_out' contains a comma"
  [[ "$profile_out" == /* || "$profile_out" == ./* || "$profile_out" == ../* ]] || profile_out="./$profile_out"
  plugin_arg+=",profile=$profile_out"
  # One substitution per assignment: its status is the assignment's, so set -e sees a failure.
  plugin_arg+=",profile_begin=0x$(address_of "$profile_begin")"
  plugin_arg+=",profile_end=0x$(address_of "$profile_end")"
  [[ -z "$profile_skip" ]] || plugin_arg+=",profile_skip=$profile_skip"
  [[ -z "$profile_count" ]] || plugin_arg+=",profile_count=$profile_count"
fi
for sym in "$@"; do
  plugin_arg+=",marker=0x$(address_of "$sym"):$sym"
done

# -d plugin: QEMU 7.2 prints what a plugin writes with qemu_plugin_outs only with this log
# category on (to stderr, like the semihosting output, so the two stay in order).
status=0
timeout "$timeout_s" qemu-system-arm -M "$machine" -nographic -monitor none -semihosting \
  -kernel "$elf" -d plugin -plugin "$plugin_arg" </dev/null 2>&1 || status=$?

case "$status" in
  0) ;;
  124) fail "qemu-system-arm timed out after ${timeout_s} s (LR_ICOUNT_TIMEOUT) running $elf" ;;
  1) fail "qemu-system-arm exited with status 1 running $elf on $machine: the firmware reported failure or QEMU could not start (see above)" ;;
  *) fail "qemu-system-arm exited with status $status running $elf on $machine (see above)" ;;
esac
