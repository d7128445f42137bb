#!/usr/bin/env bash
# clang-tidy (the repository's .clang-tidy) over the sources of core/ and of hal/'s MCU side,
# with the compile commands of a host build; fails on any warning. Headers are checked through
# the sources that include them (.clang-tidy: HeaderFilterRegex).
#
#   bash scripts/tidy.sh [BUILD_DIR]     (default build/debug: cmake --preset debug writes its
#                                         compile_commands.json)
#   bash scripts/tidy.sh BUILD_DIR FILE...   only these sources
#
# CLANG_TIDY=clang-tidy-14 picks the binary (default clang-tidy; CI: Debian 12's, version 14);
# LR_TIDY_JOBS sets how many run at once (default: the number of processors).
# The host-only backends of hal/ (hal/host, hal/linux, hal/usb: heap, threads, exceptions) are
# not checked.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

build="${1:-build/debug}"
[[ $# -gt 0 ]] && shift
tool="${CLANG_TIDY:-clang-tidy}"
jobs="${LR_TIDY_JOBS:-$(nproc)}"
command -v "$tool" >/dev/null 2>&1 ||
  { echo "tidy: $tool not found (Debian: apt-get install clang-tidy; scripts/setup.sh test)" >&2; exit 1; }
[[ -f "$build/compile_commands.json" ]] ||
  { echo "tidy: $build/compile_commands.json not found (cmake --preset debug writes it)" >&2; exit 1; }

# Every check .clang-tidy disables carries its reason in the comment above the list.
missing=()
while read -r check; do
  grep -qE "^#[[:space:]]+${check}[[:space:]]" .clang-tidy || missing+=("$check")
done < <(sed -n '/^Checks:/,/^[A-Za-z]/p' .clang-tidy | grep -oE '^[[:space:]]+-[a-z][a-z0-9.-]*' |
         sed 's/^[[:space:]]*-//')
if [[ ${#missing[@]} -gt 0 ]]; then
  echo "tidy: .clang-tidy disables ${missing[*]} without a reason in its comment" >&2
  exit 1
fi

if [[ $# -gt 0 ]]; then
  files=("$@")
else
  # As format.sh: git's list, or without git every such file.
  if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    list=(git ls-files -- 'core/*.cpp' 'hal/*.cpp')
  else
    list=(find core hal -type f -name '*.cpp')
  fi
  mapfile -t files < <("${list[@]}" | sort | grep -vE '^hal/(host|linux|usb)/' || true)
fi
[[ ${#files[@]} -gt 0 ]] || { echo "tidy: no sources" >&2; exit 1; }

out="$(mktemp)"
trap 'rm -f "$out"' EXIT
echo "tidy: $("$tool" --version | grep -m1 -o 'version [0-9.]*') on ${#files[@]} sources ($jobs at once)"
# One clang-tidy per source; their reports are collected, then printed once per finding (a
# header's finding is reported by every source that includes it).
status=0
printf '%s\0' "${files[@]}" |
  xargs -0 -P "$jobs" -I{} sh -c '"$1" -p "$2" --quiet "$3" 2>/dev/null || echo "tidy-failed: $3"' \
    _ "$tool" "$build" {} >"$out" || status=1
findings="$(grep -E '^[^ ].*:[0-9]+:[0-9]+: (warning|error): ' "$out" | sed "s|^$PWD/||" | sort -u || true)"
failed="$(grep '^tidy-failed: ' "$out" | sed 's/^tidy-failed: //' || true)"
if [[ -n "$findings" ]]; then
  echo "$findings" >&2
  echo "tidy: FAIL: $(wc -l <<<"$findings") finding(s) (full report: run clang-tidy -p $build on a file)" >&2
  exit 1
fi
if [[ -n "$failed" || $status != 0 ]]; then
  echo "tidy: FAIL: clang-tidy failed on: ${failed:-?}" >&2
  exit 1
fi
echo "tidy: PASS: ${#files[@]} sources and the core/ and hal/ headers they include"
