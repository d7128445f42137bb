#!/usr/bin/env bash
# clang-format (the repository's .clang-format) over every C and C++ file git knows of.
#
#   bash scripts/format.sh            rewrites the files in place
#   bash scripts/format.sh --check    changes nothing; lists the files that differ from their
#                                     formatted form and fails if there is any (CI)
#   bash scripts/format.sh [--check] FILE...   only these files
#
# CLANG_FORMAT=clang-format-14 picks the binary (default: clang-format). Every version formats a
# little differently: CI uses Debian 12's, clang-format 14 (scripts/setup.sh installs it).
# Files under a third_party/ or vendor/ folder are not the project's and are left alone.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

check=0
if [[ "${1:-}" == --check ]]; then
  check=1
  shift
fi
tool="${CLANG_FORMAT:-clang-format}"
command -v "$tool" >/dev/null 2>&1 ||
  { echo "format: $tool not found (Debian: apt-get install clang-format; scripts/setup.sh test)" >&2; exit 1; }
[[ -f .clang-format ]] || { echo "format: no .clang-format at the repository root" >&2; exit 1; }

if [[ $# -gt 0 ]]; then
  files=("$@")
else
  # The files git knows of; without git (or outside a checkout) every such file outside build/
  # and out/, so that a fresh machine checks the same sources.
  if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    list=(git ls-files -- '*.c' '*.cc' '*.cpp' '*.h' '*.hpp' '*.inc' '*.ipp')
  else
    list=(find . \( -path ./build -o -path ./out -o -path ./.git \) -prune -o -type f
          \( -name '*.c' -o -name '*.cc' -o -name '*.cpp' -o -name '*.h' -o -name '*.hpp'
          -o -name '*.inc' -o -name '*.ipp' \) -printf '%P\n')
  fi
  mapfile -t files < <("${list[@]}" | sort | grep -vE '(^|/)(third_party|vendor)/' || true)
fi
[[ ${#files[@]} -gt 0 ]] || { echo "format: no C/C++ files found" >&2; exit 1; }

if [[ $check == 0 ]]; then
  printf '%s\0' "${files[@]}" | xargs -0 -n 50 "$tool" -i --style=file
  echo "format: ${#files[@]} files formatted with $("$tool" --version | head -n 1)"
  exit 0
fi

# --check: compare each file with its formatted form (no --dry-run -Werror: its output is one
# warning per changed line, not per file).
bad=()
for f in "${files[@]}"; do
  if ! "$tool" --style=file "$f" | cmp -s - "$f"; then
    bad+=("$f")
  fi
done
if [[ ${#bad[@]} -gt 0 ]]; then
  echo "format: ${#bad[@]} of ${#files[@]} files are not clang-formatted:" >&2
  printf '  %s\n' "${bad[@]}" >&2
  echo "format: bash scripts/format.sh applies the changes (git diff shows them)" >&2
  exit 1
fi
echo "format: ${#files[@]} files clean ($("$tool" --version | head -n 1))"
