#!/bin/bash
# Installs what is missing, builds the release configuration and renders the demo scene:
# the project's 4,000-triangle torus knot in the classic "gold" material -> out/demo.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh demo
cmake -S . -B build/demo -DCMAKE_BUILD_TYPE=Release -DLR_HOST=ON -DLR_BENCH=OFF -DLR_TESTS=OFF >/dev/null
cmake --build build/demo -j"$(nproc)" --target lineraster-sim
mkdir -p out
./build/demo/host_sim/lineraster-sim --obj tests/host/data/torus_knot.obj --fit --material gold \
  --out out/demo.png --stats
echo "demo: wrote $(pwd)/out/demo.png"
