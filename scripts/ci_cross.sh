#!/usr/bin/env bash
# Cross-compile guard: builds the core and the smoke firmware for Cortex-M4F (the cortex-m4f
# preset: toolchain/cortex-m4f.cmake, LR_HOST=OFF) and checks that the linked firmware holds no
# heap and no exception machinery.
#
# Usage: scripts/ci_cross.sh            (from any directory)
#   LR_CROSS_RUN_QEMU=1 scripts/ci_cross.sh   also runs the ELF under qemu-system-arm
#                                             (mps2-an386, semihosting) and fails if it fails
# Extra compiler flags: CXXFLAGS in the environment (read at the first configure of
# build/cortex-m4f; see toolchain/cortex-m4f.cmake). Never -DCMAKE_CXX_FLAGS.
# Exit status: 0 on success, 1 on any failure (with a message saying which).
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

preset=cortex-m4f
build_dir="build/$preset"
elf="$build_dir/firmware/lr_smoke.elf"

fail() {
  echo "ci_cross: FAIL: $*" >&2
  exit 1
}

for tool in arm-none-eabi-g++ arm-none-eabi-gcc arm-none-eabi-nm arm-none-eabi-size; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    fail "$tool not found on PATH. Install the Arm GNU toolchain (Debian/Ubuntu: gcc-arm-none-eabi," \
      "libnewlib-arm-none-eabi, libstdc++-arm-none-eabi-newlib; the project's setup script does this)."
  fi
done
command -v cmake >/dev/null 2>&1 || fail "cmake not found on PATH"

echo "ci_cross: $(arm-none-eabi-g++ --version | head -n 1)"
echo "ci_cross: configuring preset $preset"
cmake --preset "$preset" || fail "configure of preset $preset failed"
echo "ci_cross: building preset $preset"
cmake --build --preset "$preset" --parallel || fail "cross build failed (see the compiler output above)"

[[ -f "$elf" ]] || fail "expected firmware ELF not found: $elf"

# Symbols that mean a heap or exception support got linked in, defined (T, W, ...) or not (U).
#   malloc family and the newlib reentrant variants, the heap's sbrk,
#   operator new/delete (32-bit size_t: _Znwj, _Znaj, plus the nothrow and aligned forms),
#   exception allocation and throwing.
forbidden_re='^(malloc|free|calloc|realloc|memalign|aligned_alloc|posix_memalign|_sbrk|sbrk|_sbrk_r|_malloc_r|_free_r|_calloc_r|_realloc_r|_Znwj|_Znaj|_ZdlPv|_ZdaPv|_Znw.*|_Zna.*|_ZdlPv.*|_ZdaPv.*|__cxa_allocate_exception|__cxa_throw|__cxa_begin_catch)$'

symbols="$(arm-none-eabi-nm "$elf")" || fail "arm-none-eabi-nm could not read $elf"
# nm lines: "<address> <type> <name>" or "         U <name>": the name is the last field.
found="$(awk '{print $NF}' <<<"$symbols" | grep -E "$forbidden_re" || true)"

echo "ci_cross: size of $elf"
arm-none-eabi-size "$elf"

if [[ -n "$found" ]]; then
  echo "ci_cross: forbidden symbols in $elf:" >&2
  grep -E " ($(tr '\n' '|' <<<"$found" | sed 's/|$//'))\$" <<<"$symbols" | sed 's/^/    /' >&2
  fail "the firmware links heap or exception support (see the map file $build_dir/firmware/lr_smoke.map, --cref section, for who references it)"
fi
echo "ci_cross: no malloc/free/_sbrk/_malloc_r/operator new/__cxa_allocate_exception in $elf"

if [[ "${LR_CROSS_RUN_QEMU:-0}" == 1 ]]; then
  command -v qemu-system-arm >/dev/null 2>&1 || fail "LR_CROSS_RUN_QEMU=1 but qemu-system-arm is not installed"
  echo "ci_cross: running $elf under qemu-system-arm -M mps2-an386"
  # Semihosting output arrives on QEMU's stderr.
  qemu_out="$(timeout 60 qemu-system-arm -M mps2-an386 -nographic -monitor none -semihosting -kernel "$elf" 2>&1)" \
    || { echo "$qemu_out"; fail "the smoke firmware failed under QEMU (status $?)"; }
  echo "$qemu_out"
  # The same main.cpp built for the host (tests/firmware_host): the frames must be bit-identical.
  if [[ -n "${LR_HOST_SMOKE:-}" ]]; then
    host_out="$("$LR_HOST_SMOKE")" || fail "the host build of the smoke firmware failed: $host_out"
    target_sum="$(grep -o 'checksum.*' <<<"$qemu_out")"
    host_sum="$(grep -o 'checksum.*' <<<"$host_out")"
    [[ -n "$target_sum" && "$target_sum" == "$host_sum" ]] \
      || fail "frame differs between Cortex-M4F ($target_sum) and the host ($host_sum)"
    echo "ci_cross: Cortex-M4F frame == host frame ($target_sum)"
  fi
fi

echo "ci_cross: PASS"
