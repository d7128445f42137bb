#!/usr/bin/env bash
# 64-bit ARM Linux run (bit-identical frames on every platform, as scripts/ci_armhf.sh for 32-bit
# ARM): builds the core and the core's tests for arm64 (the aarch64 preset:
# toolchain/aarch64-linux-gnu.cmake, LR_DISPLAY_BACKENDS and LR_BENCH off) and runs them under
# qemu-aarch64. core_frame_hash_test compares each pinned scene's frame hash with the x86-64
# debug build's, computed first in this run (scripts/lib/x86_frame_hashes.sh), so a pass means
# the AArch64 frames equal the x86-64 ones byte for byte.
#
# Only the core's test executables are built (tests/core/CMakeLists.txt; they pull in lr_core,
# lr_hal, lr_host and lr_reference): the whole suite takes several times longer to compile on
# two cores, and the 32-bit run (scripts/ci_armhf.sh) runs the hal and host tests on ARM too. About 3-4 minutes
# from an empty build tree on 2 cores, nearly all of it compiling; the tests take seconds.
# The executables run directly under the emulator (scripts/lib/cross_tests.sh), $(nproc) at a
# time, each with its whole GoogleTest output in build/aarch64/test-logs.
#
# Usage: scripts/ci_aarch64.sh            (from any directory; scripts/setup.sh test installs
#                                          g++-aarch64-linux-gnu and qemu-user)
#   LR_AARCH64_TESTS="core_frame_hash_test" scripts/ci_aarch64.sh   run a subset
#   LR_HOST_FRAME_HASH_TEST   the x86-64 frame-hash test (default: build/debug's, built if needed)
# GoogleTest, libpng and zlib for arm64: scripts/armhf_sysroot.sh --arch arm64 (a private
# folder, build/arm64-sysroot; the host's dpkg is not touched).
# Exit status: 0 on success, 1 on any failure (with a message saying which).
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
preset=aarch64
build="$repo_root/build/aarch64"
jobs=$(nproc)
start=$SECONDS
tests=(core_math_test core_raster_rules_test core_accuracy_test core_clipping_test
       core_capacity_test core_depth_test core_watertight_test core_texture_test
       core_phong_test core_phong_accuracy_test core_frame_hash_test core_frame_accuracy_test)
if [ -n "${LR_AARCH64_TESTS:-}" ]; then
  read -r -a tests <<<"$LR_AARCH64_TESTS"
fi

fail() {
  echo "ci_aarch64: FAIL: $*" >&2
  exit 1
}
elapsed() {
  echo "ci_aarch64: $1 took $((SECONDS - $2)) s"
}

for tool in aarch64-linux-gnu-g++ aarch64-linux-gnu-gcc qemu-aarch64 cmake; do
  command -v "$tool" >/dev/null 2>&1 \
    || fail "$tool not found on PATH (Debian: g++-aarch64-linux-gnu, qemu-user; scripts/setup.sh test installs them)"
done
echo "ci_aarch64: $(aarch64-linux-gnu-g++ --version | head -n 1); $(qemu-aarch64 --version | head -n 1)"

t=$SECONDS
bash scripts/armhf_sysroot.sh --arch arm64 \
  || fail "could not build the arm64 sysroot (scripts/armhf_sysroot.sh --arch arm64)"
elapsed "sysroot" "$t"

t=$SECONDS
cmake --preset "$preset" -DCMAKE_GTEST_DISCOVER_TESTS_DISCOVERY_MODE=PRE_TEST -DLR_DISPLAY_BACKENDS=OFF \
  -DLR_BENCH=OFF >/dev/null \
  || fail "configure of preset $preset failed"
cmake --build --preset "$preset" -j"$jobs" --target "${tests[@]}" \
  || fail "aarch64 build failed (see the compiler output above)"
elapsed "configure + build (${#tests[@]} test executables)" "$t"

# The x86-64 frames' hashes, which core_frame_hash_test under qemu-aarch64 compares with its own.
# shellcheck source=scripts/lib/x86_frame_hashes.sh
source scripts/lib/x86_frame_hashes.sh
export LR_FRAME_HASHES="$build/frame_hashes_x86_64.txt"
lr_x86_frame_hashes "$LR_FRAME_HASHES" || fail "no x86-64 frame hashes to compare with"

t=$SECONDS
# shellcheck source=scripts/lib/cross_tests.sh
source scripts/lib/cross_tests.sh
failed=0
lr_cross_tests_run ci_aarch64 "$build" qemu-aarch64 /usr/aarch64-linux-gnu "${tests[@]}" || failed=1
elapsed "tests under qemu-aarch64" "$t"
[ "$failed" = 0 ] || fail "tests failed under qemu-aarch64 (see the FAIL lines above)"
if [ -f "$build/test-logs/core_frame_hash_test.log" ]; then
  grep '^frame hash ' "$build/test-logs/core_frame_hash_test.log" | sed 's/^/  /'
fi
echo "ci_aarch64: PASS in $((SECONDS - start)) s (frames hash identically on x86-64 and 64-bit ARM)"
