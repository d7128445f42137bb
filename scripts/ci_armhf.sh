#!/usr/bin/env bash
# 32-bit ARM Linux run (frames bit-identical on every platform): builds the core, hal and host
# libraries and their tests (tests/core, tests/hal, tests/host) for armhf (the armhf preset:
# toolchain/arm-linux-gnueabihf.cmake) and runs them under qemu-arm. core_frame_hash_test
# compares each pinned scene's frame hash with the x86-64 debug build's, computed first in this
# run (scripts/lib/x86_frame_hashes.sh), so a pass means the ARM frames equal the x86-64 ones
# byte for byte.
#
# Built at -O1 (the armhf and aarch64 presets): what these runs check is the integers and frames
# of a 32-bit (64-bit) ARM target, which do not depend on the optimiser, and -O3 took 411 s of
# compilation in CI (-O1: 230 to 270 s; its tests run about 40 s longer under the emulator).
# The command-line tools' and examples' tests are left to the host builds: the whole suite took
# about 15 of CI's 40 minutes here (about 12 of them compiling at -O3 on two cores), and what
# 32-bit ARM Linux can break (int and pointer widths, the frames, the panel command streams,
# the file loaders) is in the three folders. The display backends and lr_panel_app run on a real
# 32-bit ARM kernel in scripts/ci_guest.sh. The executables run directly under the emulator
# (scripts/lib/cross_tests.sh), $(nproc) at a time, each with its output in
# build/armhf/test-logs.
#
# Usage: scripts/ci_armhf.sh            (from any directory; scripts/setup.sh test installs
#                                        g++-arm-linux-gnueabihf and qemu-user)
#   LR_ARMHF_TESTS="core_frame_hash_test" scripts/ci_armhf.sh   run a subset
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

# Test discovery at CTest time, not after each link (which would run every executable under
# the emulator once more while building).
t=$SECONDS
cmake --preset "$preset" -DCMAKE_GTEST_DISCOVER_TESTS_DISCOVERY_MODE=PRE_TEST >/dev/null \
  || fail "configure of preset $preset failed"
# shellcheck source=scripts/lib/cross_tests.sh
source scripts/lib/cross_tests.sh
if [ -n "${LR_ARMHF_TESTS:-}" ]; then
  read -r -a tests <<<"$LR_ARMHF_TESTS"
else
  mapfile -t tests < <(lr_cross_test_targets "build/$preset" core_ hal_ host_)
fi
[ ${#tests[@]} -gt 0 ] || fail "no test executable configured in build/$preset"
cmake --build --preset "$preset" -j"$jobs" --target "${tests[@]}" \
  || fail "armhf build failed (see the compiler output above)"
elapsed "configure + build (${#tests[@]} test executables)" "$t"

# The x86-64 frames' hashes, which core_frame_hash_test under qemu-arm compares with its own.
# shellcheck source=scripts/lib/x86_frame_hashes.sh
source scripts/lib/x86_frame_hashes.sh
export LR_FRAME_HASHES="$repo_root/build/$preset/frame_hashes_x86_64.txt"
lr_x86_frame_hashes "$LR_FRAME_HASHES" || fail "no x86-64 frame hashes to compare with"

t=$SECONDS
lr_cross_tests_run ci_armhf "$repo_root/build/$preset" qemu-arm /usr/arm-linux-gnueabihf "${tests[@]}" \
  || fail "tests failed under qemu-arm (see the FAIL lines above)"
elapsed "tests under qemu-arm" "$t"
echo "ci_armhf: PASS (frames hash identically on x86-64 and 32-bit ARM)"
