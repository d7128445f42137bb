#!/usr/bin/env bash
# 32-bit ARM Linux run (frames bit-identical on every platform): builds the core, the
# host simulator and the tests for armhf (the armhf preset: toolchain/arm-linux-gnueabihf.cmake)
# and runs them through CTest under qemu-arm. core_frame_hash_test compares each pinned scene's
# frame hash with the x86-64 debug build's, computed first in this run
# (scripts/lib/x86_frame_hashes.sh), so a pass means the ARM frames equal the x86-64 ones byte
# for byte.
#
# Usage: scripts/ci_armhf.sh            (from any directory; scripts/setup.sh test installs
#                                        g++-arm-linux-gnueabihf and qemu-user)
#   LR_ARMHF_CTEST_ARGS="-R FrameHash" scripts/ci_armhf.sh   run a subset
#   LR_HOST_FRAME_HASH_TEST   the x86-64 frame-hash test (default: build/debug's, built if needed)
# GoogleTest, libpng and zlib for armhf: scripts/armhf_sysroot.sh (a private folder; the host's
# dpkg is not touched). Not built for ARM: the benchmarks (LR_BENCH OFF), the GL check (no Mesa
# in the sysroot), the stress suite (__int128) -- see tests/CMakeLists.txt.
# Exit status: 0 on success, 1 on any failure (with a message saying which).
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
preset=armhf
jobs=$(nproc)

fail() {
  echo "ci_armhf: FAIL: $*" >&2
  exit 1
}
elapsed() {
  echo "ci_armhf: $1 took $((SECONDS - $2)) s"
}

for tool in arm-linux-gnueabihf-g++ arm-linux-gnueabihf-gcc qemu-arm cmake ctest; do
  command -v "$tool" >/dev/null 2>&1 \
    || fail "$tool not found on PATH (Debian: g++-arm-linux-gnueabihf, qemu-user; scripts/setup.sh test installs them)"
done
echo "ci_armhf: $(arm-linux-gnueabihf-g++ --version | head -n 1); $(qemu-arm --version | head -n 1)"

t=$SECONDS
bash scripts/armhf_sysroot.sh || fail "could not build the armhf sysroot (scripts/armhf_sysroot.sh)"
elapsed "sysroot" "$t"

t=$SECONDS
cmake --preset "$preset" >/dev/null || fail "configure of preset $preset failed"
cmake --build --preset "$preset" -j"$jobs" || fail "armhf build failed (see the compiler output above)"
elapsed "configure + build" "$t"

# The x86-64 frames' hashes, which core_frame_hash_test under qemu-arm compares with its own.
# shellcheck source=scripts/lib/x86_frame_hashes.sh
source scripts/lib/x86_frame_hashes.sh
export LR_FRAME_HASHES="$repo_root/build/$preset/frame_hashes_x86_64.txt"
lr_x86_frame_hashes "$LR_FRAME_HASHES" || fail "no x86-64 frame hashes to compare with"

t=$SECONDS
# shellcheck disable=SC2086  # word splitting of the extra arguments is intended
ctest --preset "$preset" -j"$jobs" ${LR_ARMHF_CTEST_ARGS:-} || fail "tests failed under qemu-arm"
elapsed "tests under qemu-arm" "$t"
echo "ci_armhf: PASS (frames hash identically on x86-64 and 32-bit ARM)"
