#!/bin/bash
# The three ways a project uses lineraster, each an out-of-tree project of tests/consumers that
# builds examples/host/minimal.cpp against this checkout, runs it and checks pixels of its frame
# (tests/consumers/check_ppm.py):
#   subdirectory  add_subdirectory(<checkout>)
#   fetchcontent  FetchContent from this repository at HEAD (commit first: the working tree's
#                 changes are not fetched)
#   package       find_package(lineraster) on a prefix installed from this checkout
#   bare_metal    examples/bare_metal cross-built for Cortex-M4F with its own toolchain file
#                 (examples/bare_metal/cortex-m4f.cmake) on a prefix installed with the same
#                 file, run under QEMU (mps2-an386): it checks its own pixels and exits non-zero
#                 through semihosting when they are wrong
# Every configure disables GoogleTest, Google Benchmark, libpng and libjpeg
# (CMAKE_DISABLE_FIND_PACKAGE_*): a consumer of the core needs none of them.
#   scripts/consumers.sh [WORK_DIR]   (default build/consumers)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
work=${1:-build/consumers}
jobs=$(nproc)
rm -rf "$work"
mkdir -p "$work"
work=$(cd "$work" && pwd)
no_deps=(-DCMAKE_DISABLE_FIND_PACKAGE_GTest=ON -DCMAKE_DISABLE_FIND_PACKAGE_benchmark=ON
         -DCMAKE_DISABLE_FIND_PACKAGE_PNG=ON -DCMAKE_DISABLE_FIND_PACKAGE_JPEG=ON
         -DCMAKE_BUILD_TYPE=Release)

fail() { echo "consumers: $*" >&2; exit 1; }

# consumer NAME [CMAKE ARGS...]: configure, build, run, check.
consumer() {
  local name=$1 dir=$work/$1
  shift
  cmake -S tests/consumers/"$name" -B "$dir" "${no_deps[@]}" "$@" > "$dir.log" 2>&1 \
    || { cat "$dir.log"; fail "$name: configure failed"; }
  cmake --build "$dir" -j"$jobs" >> "$dir.log" 2>&1 || { cat "$dir.log"; fail "$name: build failed"; }
  # Only the library and the example: nothing of the project's tests, tools or firmware.
  if grep -qE "Built target (lr_core_test|core_|lineraster-sim|lr_host)" "$dir.log"; then
    fail "$name: built more than the library (see $dir.log)"
  fi
  "$dir/minimal" "$dir/frame.ppm" || fail "$name: the example failed"
  python3 tests/consumers/check_ppm.py "$dir/frame.ppm" || fail "$name: wrong frame"
  echo "consumers: $name: ok"
}

consumer subdirectory -DLINERASTER_DIR="$root"

[ -z "$(git status --porcelain --untracked-files=no)" ] \
  || echo "consumers: fetchcontent fetches HEAD ($(git rev-parse --short HEAD)), not the working tree's changes"
consumer fetchcontent -DLINERASTER_GIT="$root" -DLINERASTER_TAG="$(git rev-parse HEAD)"

# The installation: the libraries as a user installs them (no host tools, tests or benchmarks).
cmake -S . -B "$work/install-build" "${no_deps[@]}" -DLR_HOST=OFF -DLR_TESTS=OFF -DLR_BENCH=OFF \
  > "$work/install.log" 2>&1 || { cat "$work/install.log"; fail "install: configure failed"; }
cmake --build "$work/install-build" -j"$jobs" >> "$work/install.log" 2>&1 \
  || { cat "$work/install.log"; fail "install: build failed"; }
cmake --install "$work/install-build" --prefix "$work/prefix" >> "$work/install.log" 2>&1 \
  || { cat "$work/install.log"; fail "install failed"; }
for f in include/lineraster/lineraster.hpp include/lineraster/core/raster/renderer.hpp \
         include/lineraster/hal/panel.hpp lib/cmake/lineraster/lineraster-config.cmake \
         lib/cmake/lineraster/lineraster-config-version.cmake; do
  [ -f "$work/prefix/$f" ] || fail "install: $f missing"
done
[ ! -e "$work/prefix/include/lineraster/core/CMakeLists.txt" ] || fail "install: sources installed"
consumer package -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DLINERASTER_EXAMPLE="$root/examples/host/minimal.cpp"

# Bare metal: the library cross-built and installed as a firmware project would, with nothing of
# the project's toolchain files or presets.
tc=$root/examples/bare_metal/cortex-m4f.cmake
cmake -S . -B "$work/bm-lib" -DCMAKE_TOOLCHAIN_FILE="$tc" -DCMAKE_BUILD_TYPE=Release \
  > "$work/bare_metal.log" 2>&1 || { cat "$work/bare_metal.log"; fail "bare_metal: library configure failed"; }
cmake --build "$work/bm-lib" -j"$jobs" >> "$work/bare_metal.log" 2>&1 \
  || { cat "$work/bare_metal.log"; fail "bare_metal: library build failed"; }
if grep "Built target" "$work/bare_metal.log" | grep -qvE "Built target (lr_core|lr_hal)$"; then
  fail "bare_metal: built more than the library (see $work/bare_metal.log)"
fi
cmake --install "$work/bm-lib" --prefix "$work/bm-prefix" >> "$work/bare_metal.log" 2>&1 \
  || { cat "$work/bare_metal.log"; fail "bare_metal: install failed"; }
cmake -S examples/bare_metal -B "$work/bare_metal" -DCMAKE_TOOLCHAIN_FILE="$tc" \
  -DCMAKE_PREFIX_PATH="$work/bm-prefix" -DCMAKE_BUILD_TYPE=Release >> "$work/bare_metal.log" 2>&1 \
  || { cat "$work/bare_metal.log"; fail "bare_metal: configure failed"; }
cmake --build "$work/bare_metal" >> "$work/bare_metal.log" 2>&1 \
  || { cat "$work/bare_metal.log"; fail "bare_metal: build failed"; }
# Semihosting output arrives on QEMU's stderr; the exit status is the example's verdict.
out=$(timeout 120 qemu-system-arm -M mps2-an386 -nographic -monitor none -semihosting \
  -kernel "$work/bare_metal/minimal.elf" 2>&1) || fail "bare_metal: the example failed under QEMU: $out"
[[ $out == *"pixels as expected"* ]] || fail "bare_metal: unexpected output: $out"
echo "consumers: bare_metal: ok ($out)"
echo "consumers: the three ways and the bare-metal package build and draw the examples' frames"
