#!/bin/bash
# Installs what is missing, builds and runs every test: the debug build, the same suite under
# AddressSanitizer + UndefinedBehaviorSanitizer, the Cortex-M4F cross build with its link guard,
# the 32-bit ARM Linux build run under qemu-arm (frames hash as on x86-64), and the frame
# benchmark's figures (printed, never asserted).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh test
jobs=$(nproc)

echo "== debug build + tests"
cmake --preset debug >/dev/null
cmake --build --preset debug -j"$jobs"
ctest --preset debug -j"$jobs"

echo "== ASan + UBSan build + tests"
cmake --preset asan >/dev/null
cmake --build --preset asan -j"$jobs"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --preset asan -j"$jobs"

echo "== Cortex-M4F cross build + link guard + run under QEMU, frame compared with the host's"
LR_CROSS_RUN_QEMU=1 LR_HOST_SMOKE=build/debug/tests/firmware_host/lr_smoke_host bash scripts/ci_cross.sh

echo "== 32-bit ARM Linux build + tests under qemu-arm, frames hashed against x86-64's"
bash scripts/ci_armhf.sh
bash scripts/ci_guest.sh  # the Linux display backends in an emulated ARM Linux guest (qemu-system-arm)

echo "== fuzzing: libFuzzer targets (clang, ASan + UBSan), a fixed number of runs from a fixed seed; crashes become regressions"
bash scripts/fuzz.sh --ci

echo "== figures (benchmarks print, they do not pass or fail)"
cmake --preset release >/dev/null
cmake --build --preset release -j"$jobs" --target lr_frame_bench
./build/release/tests/bench/lr_frame_bench --benchmark_min_time=0.2
bash scripts/count_instructions.sh build/release
bash scripts/texture_bench.sh
bash scripts/quality_bench.sh
bash scripts/lighting_bench.sh
echo "== all tests passed"
