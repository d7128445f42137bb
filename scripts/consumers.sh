#!/bin/bash
# The ways a project uses lineraster, each an out-of-tree project of tests/consumers that builds
# against this checkout, runs and checks what it made:
#   subdirectory  add_subdirectory(<checkout>)                      examples/host/minimal.cpp
#   fetchcontent  FetchContent from this repository at HEAD (commit  the same
#                 first: the working tree's changes are not fetched)
# and find_package(lineraster) on a prefix installed from this checkout as a user installs it
# (docs/install.md: the `use` preset, lr_package built as scripts/demo.sh builds it, host tools on):
#   package       lr::core                                          the same
#   hal           lr::hal: lr::Panel and PanelSink over a recording PanelBus; the bytes against the
#                 ST7789's commands (start-up, address window, pixels, a skipped second frame)
#   host          lr::host: an OBJ + MTL, a PNG texture and a JPEG loaded; every installed header
#                 compiled in one translation unit
#   asset         the installed lineraster-asset converts a two-material textured OBJ at build
#                 time; its header compiled with lr::core under firmware flags, rendered, and the
#                 frame's pixels compared with the two textures' texels (check_textured.py)
#   bare_metal    examples/bare_metal cross-built for Cortex-M4F with its own toolchain file
#                 (examples/bare_metal/cortex-m4f.cmake) on a prefix installed with the same
#                 file, run under QEMU (mps2-an386): it checks its own pixels and exits non-zero
#                 through semihosting when they are wrong
# Every configure disables GoogleTest and Google Benchmark (CMAKE_DISABLE_FIND_PACKAGE_*), and
# every consumer but those that use lr::host (package without components, host) libpng and
# libjpeg: a consumer of the core needs none of them.
#   scripts/consumers.sh [WORK_DIR]   (default build/consumers)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
work=${1:-build/consumers}
jobs=$(nproc)
rm -rf "$work"
mkdir -p "$work"
work=$(cd "$work" && pwd)
# Release builds at -O0: what is checked here is how the library is found, built and linked, not
# the optimiser, and each hosted build compiles lr_core's renderer instances (one of them about
# 30 s of a CPU at -O3, 16 s at -O1, 5 s at -O0).
no_tests=(-DCMAKE_DISABLE_FIND_PACKAGE_GTest=ON -DCMAKE_DISABLE_FIND_PACKAGE_benchmark=ON
          -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS_RELEASE="-O0 -DNDEBUG"
          -DCMAKE_CXX_FLAGS_RELEASE="-O0 -DNDEBUG")
no_images=(-DCMAKE_DISABLE_FIND_PACKAGE_PNG=ON -DCMAKE_DISABLE_FIND_PACKAGE_JPEG=ON)

fail() { echo "consumers: $*" >&2; exit 1; }

# build NAME [CMAKE ARGS...]: configure and build tests/consumers/NAME in WORK/NAME.
build() {
  local name=$1 dir=$work/$1
  shift
  cmake -S tests/consumers/"$name" -B "$dir" "${no_tests[@]}" "$@" > "$dir.log" 2>&1 \
    || { cat "$dir.log"; fail "$name: configure failed"; }
  cmake --build "$dir" -j"$jobs" >> "$dir.log" 2>&1 || { cat "$dir.log"; fail "$name: build failed"; }
  # Only the library and the consumer: nothing of the project's tests, tools or firmware.
  if grep -qE "Built target (lr_core_test|core_|lineraster-sim|lineraster-asset|lr_host)" "$dir.log"; then
    fail "$name: built more than the library (see $dir.log)"
  fi
}

# minimal NAME [CMAKE ARGS...]: build, run examples/host/minimal.cpp, check its frame.
minimal() {
  local name=$1 dir=$work/$1
  build "$@"
  "$dir/minimal" "$dir/frame.ppm" || fail "$name: the example failed"
  python3 tests/consumers/check_ppm.py "$dir/frame.ppm" || fail "$name: wrong frame"
  echo "consumers: $name: ok"
}

minimal subdirectory "${no_images[@]}" -DLINERASTER_DIR="$root"

[ -z "$(git status --porcelain --untracked-files=no)" ] \
  || echo "consumers: fetchcontent fetches HEAD ($(git rev-parse --short HEAD)), not the working tree's changes"
minimal fetchcontent "${no_images[@]}" -DLINERASTER_GIT="$root" -DLINERASTER_TAG="$(git rev-parse HEAD)"

# The installation as docs/install.md tells a user to make it: the `use` preset (host tools on,
# no tests or benchmarks), lr_package built (what scripts/demo.sh builds), `cmake --install`.
prefix=$work/prefix
cmake --preset use -B "$work/install-build" "${no_tests[@]}" > "$work/install.log" 2>&1 \
  || { cat "$work/install.log"; fail "install: configure failed"; }
cmake --build "$work/install-build" -j"$jobs" --target lr_package >> "$work/install.log" 2>&1 \
  || { cat "$work/install.log"; fail "install: build failed"; }
# lr_package: the libraries, the two tools and what they link; no tests, benchmarks or firmware.
built=$(grep -oE "Built target [A-Za-z0-9_-]+" "$work/install.log" | cut -d' ' -f3 | sort | tr '\n' ' ')
for t in $built; do
  case $t in
    lr_core|lr_hal|lr_host|lr_asset_writer|lr_frame_files|lr_display_spec|lr_hal_*) ;;  # lr_hal_*: backends
    lineraster-sim|lineraster-asset|lr_package) ;;
    *) fail "install: lr_package built $t (all: $built)" ;;
  esac
done
cmake --install "$work/install-build" --prefix "$prefix" >> "$work/install.log" 2>&1 \
  || { cat "$work/install.log"; fail "install failed"; }
for f in include/lineraster/lineraster.hpp include/lineraster/core/raster/renderer.hpp \
         include/lineraster/hal/panel.hpp include/lineraster/host_sim/formats/obj_loader.hpp \
         lib/cmake/lineraster/lineraster-config.cmake \
         lib/cmake/lineraster/lineraster-config-version.cmake bin/lineraster-sim bin/lineraster-asset; do
  [ -f "$prefix/$f" ] || fail "install: $f missing"
done
[ ! -e "$prefix/include/lineraster/core/CMakeLists.txt" ] || fail "install: sources installed"
[ ! -e "$prefix/include/lineraster/host_sim/programs" ] || fail "install: the tools' own headers installed"

minimal package -DCMAKE_PREFIX_PATH="$prefix" -DLINERASTER_EXAMPLE="$root/examples/host/minimal.cpp"

build hal "${no_images[@]}" -DCMAKE_PREFIX_PATH="$prefix"
"$work/hal/panel_bytes" || fail "hal: the panel did not get the expected bytes"
echo "consumers: hal: ok"

build host -DCMAKE_PREFIX_PATH="$prefix"
"$work/host/load_files" "$root/tests/host/data" "$root/tests/fuzz/corpus/png/jpeg_0.jpg" \
  || fail "host: the files did not load as expected"
echo "consumers: host: ok"

data=$root/tests/host/data
build asset "${no_images[@]}" -DCMAKE_PREFIX_PATH="$prefix" \
  -DLINERASTER_MODEL="$data/quirks/two_textures.obj"
"$work/asset/textured" "$work/asset/frame.ppm" || fail "asset: the program failed"
python3 tests/consumers/check_textured.py "$work/asset/frame.ppm" "$data/checker.png" \
  "$data/tiles64.png" || fail "asset: wrong frame"
echo "consumers: asset: ok"

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
echo "consumers: the three ways, every installed target and the bare-metal package work"
