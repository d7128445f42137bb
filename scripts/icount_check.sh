#!/usr/bin/env bash
# Proves the instruction-counting plugin (tools/qemu_icount) exact: runs the firmware
# firmware/icount_check (lr_icount_check.elf) under scripts/icount.sh, pairs each begin marker line
# with the next lr_icount_end line, and checks that every difference equals the count the firmware
# printed for that case; then runs it again and checks that every marker line and the total are
# identical from run to run.
#
# Usage: scripts/icount_check.sh [--plugin SO] [--machine M] [--runs N] [--skip-missing] ELF
#   ELF             e.g. build/cortex-m4f/firmware/icount_check/lr_icount_check.elf
#                   (cmake --preset cortex-m4f && cmake --build --preset cortex-m4f -j2)
#   --machine M     QEMU machine; default: the name in lr_icount_check.machine next to the ELF
#                   (written by firmware/icount_check/CMakeLists.txt), else mps2-an386
#   --plugin SO     passed to scripts/icount.sh (default there: LR_ICOUNT_PLUGIN or the release build's)
#   --runs N        how many runs must agree (default 2, at least 1)
#   --skip-missing  exit 77 (CTest's skip) instead of failing when the ELF, the plugin or
#                   qemu-system-arm is missing
# Exit status: 0 PASS, 1 FAIL (with the reason), 77 skipped (--skip-missing only).
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

fail() {
  echo "icount_check: FAIL: $*" >&2
  exit 1
}
usage() {
  echo "usage: scripts/icount_check.sh [--plugin SO] [--machine M] [--runs N] [--skip-missing] ELF" >&2
  exit 1
}

plugin_opt=()
# Default: the release build's plugin, else the debug build's (scripts/test.sh builds that one).
plugin="${LR_ICOUNT_PLUGIN:-$repo_root/build/release/tools/qemu_icount/libqemu_icount.so}"
if [[ -z "${LR_ICOUNT_PLUGIN:-}" && ! -f "$plugin" ]]; then
  plugin="$repo_root/build/debug/tools/qemu_icount/libqemu_icount.so"
fi
machine=""
runs=2
skip_missing=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --plugin) [[ $# -ge 2 ]] || usage; plugin="$2"; plugin_opt=(--plugin "$2"); shift 2 ;;
    --machine) [[ $# -ge 2 ]] || usage; machine="$2"; shift 2 ;;
    --runs) [[ $# -ge 2 && "$2" =~ ^[1-9][0-9]*$ ]] || usage; runs="$2"; shift 2 ;;
    --skip-missing) skip_missing=1; shift ;;
    -*) echo "icount_check: unknown option $1" >&2; usage ;;
    *) break ;;
  esac
done
[[ $# -eq 1 ]] || usage
elf="$1"

missing() {
  if [[ "$skip_missing" == 1 ]]; then
    echo "icount_check: SKIP: $*"
    exit 77
  fi
  fail "$*"
}
[[ -f "$elf" ]] || missing "$elf not built (cmake --preset cortex-m4f && cmake --build --preset cortex-m4f -j2)"
[[ -f "$plugin" ]] || missing "plugin $plugin not built (cmake --build --preset release --target lr_qemu_icount)"
command -v qemu-system-arm >/dev/null 2>&1 || missing "qemu-system-arm not installed"

if [[ -z "$machine" ]]; then
  machine_file="${elf%.elf}.machine"
  if [[ -f "$machine_file" ]]; then
    machine="$(tr -d '[:space:]' <"$machine_file")"
  else
    machine=mps2-an386
  fi
fi

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

echo "icount_check: $elf on $machine, $runs runs"
for ((run = 1; run <= runs; ++run)); do
  if ! "$repo_root/scripts/icount.sh" "${plugin_opt[@]}" --machine "$machine" "$elf" \
      lr_icount_begin lr_icount_begin4 lr_icount_end >"$work/run$run.txt" 2>"$work/run$run.err"; then
    cat "$work/run$run.txt" "$work/run$run.err" >&2
    fail "run $run: $(tail -n 1 "$work/run$run.err")"
  fi
done

# Run 1: the measured differences against the expected counts, case by case.
#   icount: marker 0xADDR NAME at COUNT       (the plugin, through icount.sh)
#   icount_check: case NAME expected N        (the firmware, after each region)
#   icount_check: done CASES
report="$(awk '
  /^icount: marker 0x[0-9a-f]+ [^ ]+ at [0-9]+$/ {
    if ($4 ~ /^lr_icount_begin/) {
      if (open) { print "ERROR two begin markers without an end (" $4 " at " $6 ")"; exit }
      open = 1; begin = $6
    } else if ($4 == "lr_icount_end") {
      if (!open) { print "ERROR lr_icount_end at " $6 " without a begin marker"; exit }
      open = 0; measured[++n_measured] = $6 - begin
    }
    next
  }
  /^icount_check: case [^ ]+ expected [0-9]+$/ { name[++n_cases] = $3; expected[n_cases] = $5; next }
  /^icount_check: done [0-9]+$/ { done = $3; next }
  END {
    if (done == "") { print "ERROR the firmware did not print \"icount_check: done\""; exit }
    if (done != n_cases) { print "ERROR the firmware ran " done " cases but printed " n_cases; exit }
    if (n_measured != n_cases) { print "ERROR " n_measured " measured regions for " n_cases " cases"; exit }
    bad = 0
    for (i = 1; i <= n_cases; ++i) {
      ok = (measured[i] == expected[i]) ? "ok" : "MISMATCH"
      if (ok != "ok") ++bad
      printf "  %-12s expected %9d  measured %9d  %s\n", name[i], expected[i], measured[i], ok
    }
    if (bad) print "ERROR " bad " of " n_cases " cases differ"
  }' "$work/run1.txt")"
echo "$report"
if grep -q '^ERROR' <<<"$report"; then
  echo "--- output of run 1:" >&2
  cat "$work/run1.txt" >&2
  fail "$(grep '^ERROR' <<<"$report" | head -n 1 | sed 's/^ERROR //')"
fi

# Every run: the same marker lines (absolute counts) and the same total.
grep '^icount: ' "$work/run1.txt" >"$work/counts1.txt" || true
total="$(sed -n 's/^icount: total \([0-9]*\) instructions$/\1/p' "$work/counts1.txt")"
[[ -n "$total" ]] || fail "run 1: no 'icount: total' line"
for ((run = 2; run <= runs; ++run)); do
  grep '^icount: ' "$work/run$run.txt" >"$work/counts$run.txt" || true
  if ! diff -u "$work/counts1.txt" "$work/counts$run.txt" >"$work/diff.txt"; then
    cat "$work/diff.txt" >&2
    fail "run $run's counts differ from run 1's"
  fi
done
echo "icount_check: $(grep -c '^icount: marker' "$work/counts1.txt") marker lines and the total ($total instructions) identical in $runs runs"
echo "icount_check: PASS"
