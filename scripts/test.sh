#!/bin/bash
# Installs what is missing, checks the sources (clang-format, clang-tidy, the include layers),
# builds and runs every test: a Release build of every target (GCC -O3) with its tests, the
# same suite under AddressSanitizer + UndefinedBehaviorSanitizer (Clang, -O0), the bare-metal
# builds for Cortex-M0+, M4F, M7 and M33 run under QEMU (smoke, fault, demo frames against lineraster-sim, the bunny in the micro:bit's
# 16 KB, instruction-count check, footprint with its link and stack guards), the consumer
# projects (examples/ built by add_subdirectory, FetchContent, find_package and cross-built from
# an installed package), the 32-bit ARM Linux core, hal and host tests under qemu-arm, the ARM
# Linux guest, the 64-bit ARM Linux core tests, the fuzzers' fixed runs, and the benchmarks'
# figures (printed, never asserted). Each step prints its duration.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh test
jobs=$(nproc)

step_name=""
step_start=$SECONDS
step() {
  [[ -n "$step_name" ]] && echo "== done: $step_name ($((SECONDS - step_start)) s)"
  step_name="$1"
  step_start=$SECONDS
  [[ -n "$step_name" ]] && echo "== $step_name"
  return 0
}

# Source checks first (they need only the debug tree's compile_commands.json). A failure is
# reported here and fails the run at the end, after every test has run: a formatting slip does
# not hide the test results.
step "source checks: clang-format, clang-tidy (core/, hal/), include layers, documentation links"
cmake --preset debug >/dev/null
source_failures=()
bash scripts/format.sh --check || source_failures+=("clang-format (bash scripts/format.sh)")
bash scripts/tidy.sh build/debug || source_failures+=("clang-tidy (bash scripts/tidy.sh)")
python3 scripts/check_layers.py || source_failures+=("include layers (python3 scripts/check_layers.py --matrix)")
python3 scripts/check_doc_links.py || source_failures+=("documentation links and included examples (python3 scripts/check_doc_links.py)")

# One GCC build of every target, at -O3 (GCC warns there where -O0 does not: a plain Release
# build of everything must pass), tests run in it, and its programs serve the later steps. (A
# GCC -O0 build besides it took 3.5 minutes of CI and found nothing the others do not: the core
# has no assert, no NDEBUG path; Clang builds at -O0 below, the cross builds at -O1 and -O3.) The
# test programs' own code is compiled at -O0 here (tests/CMakeLists.txt: LR_TEST_RELEASE_OPTIONS).
step "Release build of every target (GCC -O3, warnings are errors) + tests"
cmake --preset release >/dev/null
cmake --build --preset release -j"$jobs"
ctest --preset release -j"$jobs"
# Host programs the later steps use: the CLI, the converter, the instruction-counting plugin,
# the host builds of the smoke, peer and benchmark firmware, and the x86-64 frame-hash test the
# ARM runs compare with.
host=build/release
export LR_HOST_TOOLS_DIR="$PWD/$host" LR_SIM="$host/host_sim/lineraster-sim"
export LR_ICOUNT_PLUGIN="$PWD/$host/tools/qemu_icount/libqemu_icount.so"
export LR_HOST_FRAME_HASH_TEST="$PWD/$host/tests/core/core_frame_hash_test"
export LR_HOST_DIR="$PWD/$host/tests/firmware_host"

# At -O0 (the asan preset is a Debug build): compiled with optimisation, the sanitizer build took
# 880 s of a 2-core CI run, -O0 a fraction of that, and the tests stay fast either way. Built with
# Clang: every target then builds with both compilers in CI (GCC: debug here, release below).
step "ASan + UBSan build (Clang) + tests"
cmake --preset asan >/dev/null
cmake --build --preset asan -j"$jobs"
# The random-triangle stress runs a quarter of the debug run's triangles here (the same code
# paths; the debug step runs them all): about 75 s less under the sanitizers.
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  LR_STRESS_SCREEN=200000 LR_STRESS_3D=50000 ctest --preset asan -j"$jobs"

step "bare metal: Cortex-M0+, M4F, M7, M33 builds, link guard, smoke and fault checks under QEMU"
LR_CROSS_RUN_QEMU=1 LR_HOST_SMOKE=$host/tests/firmware_host/lr_smoke_host bash scripts/ci_cross.sh

step "bare metal: demo frames identical to lineraster-sim's, worst-case stack within the reserved stack"
bash scripts/ci_firmware.sh

step "bare metal: the peer bunnies in small RAM (S1 in the micro:bit's 16 KB, S1x in 64 KB), frames = one pass"
bash scripts/small_ram.sh build/cortex-m0plus build/cortex-m4f

step "bare metal: the instruction-counting plugin against known instruction sequences"
for core in cortex-m4f cortex-m0plus; do
  bash scripts/icount_check.sh --runs 1 "build/$core/firmware/icount_check/lr_icount_check.elf"
done

step "bare metal: footprint (flash, RAM, worst-case and measured stack) for M0+ and M4F, and M4F at -Os"
# The -Os preset (cortex-m4f-size) builds only the footprint images: their frames must be the
# -O3 images' (footprint.sh compares the checksums across every tree it is given).
cmake --preset cortex-m4f-size -DLR_HOST_TOOLS_DIR="$LR_HOST_TOOLS_DIR" >/dev/null
bash scripts/footprint.sh build/cortex-m0plus build/cortex-m4f build/cortex-m4f-size
# What the -Os build compiles differently from -O3 (lanes triangles through the shared row walk
# with the span loop by hand, the setup's rows): their checks against the C twins there.
cmake --build build/cortex-m4f-size -j"$jobs" --target lr_span_check lr_bin_check
for image in lr_span_check lr_bin_check; do
  out="$(timeout 900 qemu-system-arm -M mps2-an386 -nographic -monitor none -semihosting \
    -kernel "build/cortex-m4f-size/firmware/${image#lr_}/$image.elf" 2>&1)" || true
  echo "$out" | tail -n 3
  grep -q "^$image: PASS" <<<"$out" || { echo "test: $image failed in the -Os build" >&2; exit 1; }
done

step "consumers: add_subdirectory, FetchContent; find_package of lr::core, lr::hal, lr::host and a header from the installed lineraster-asset (host tools on); a Cortex-M4F package under QEMU; each checked"
bash scripts/consumers.sh build/consumers

step "32-bit ARM Linux: core, hal and host tests under qemu-arm, frames hashed against x86-64's"
bash scripts/ci_armhf.sh

step "32-bit ARM Linux guest: display backends and lr_panel_app against a real kernel"
bash scripts/ci_guest.sh

step "64-bit ARM Linux: core tests and frame hashes under qemu-aarch64"
bash scripts/ci_aarch64.sh

step "fuzzing: libFuzzer targets (clang, ASan + UBSan), a fixed number of runs from a fixed seed; crashes become regressions"
bash scripts/fuzz.sh --ci

step "the figures (benchmarks print, they do not pass or fail), from the Release build"
# lr_bench_host: count_instructions.sh's host counts of the Cortex-M budget cases.
./build/release/tests/bench/lr_frame_bench --benchmark_min_time=0.2
bash scripts/count_instructions.sh build/release
bash scripts/texture_bench.sh
bash scripts/quality_bench.sh
bash scripts/lighting_bench.sh
LR_BENCH_HOST=$host/tests/firmware_host/lr_bench_host bash scripts/bench_cortex_m.sh
# The peer scenes: the M4F frames against the host's only (one QEMU run, a few seconds); the
# counts per stage need a tree with line tables: scripts/peer_bench.sh's header.
LR_PEER_HOST=$host/tests/firmware_host/lr_peer_host bash scripts/peer_bench.sh --check-only build/cortex-m4f

step ""
if [[ ${#source_failures[@]} -gt 0 ]]; then
  printf '== FAIL: source check: %s\n' "${source_failures[@]}" >&2
  exit 1
fi
echo "== all tests passed ($SECONDS s)"
