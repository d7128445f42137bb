#!/bin/bash
# Installs what is missing, builds the configuration for use (the `use` preset: Release, the
# libraries and the two tools, no tests or benchmarks) in build/use and renders the demo scene:
# the project's 4,000-triangle torus knot in the classic "gold" material -> out/demo.png.
# The build holds everything the package installs: `cmake --install build/use --prefix P` next
# (docs/install.md).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh demo
cmake --preset use >/dev/null
cmake --build --preset use -j"$(nproc)"
mkdir -p out
./build/use/host_sim/lineraster-sim --obj tests/host/data/torus_knot.obj --fit --material gold \
  --out out/demo.png --stats
echo "demo: wrote $(pwd)/out/demo.png"
