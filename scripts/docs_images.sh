#!/bin/bash
# Renders the README's images with lineraster-sim (build first: cmake --preset release &&
# cmake --build --preset release). Usage: scripts/docs_images.sh [build dir]
set -euo pipefail
cd "$(dirname "$0")/.."
sim=${1:-build/release}/host_sim/lineraster-sim
out=docs/images
tmp=$(mktemp -d)
data=tests/host/data
"$sim" --obj $data/torus_knot.obj --fit --material gold --out $out/demo.png
for s in flat gouraud; do
  "$sim" --obj $data/torus_knot.obj --fit --material gold --shading $s --width 240 --height 180 --out "$tmp/$s.png"
done
python3 scripts/side_by_side.py $out/shading.png "$tmp/flat.png" "$tmp/gouraud.png"
"$sim" --obj $data/cube.obj --eye 2.2,1.8,3 --texture $data/tiles64.png --diffuse 0.9,0.9,0.9 \
  --specular 0.6,0.6,0.6 --shininess 40 --mipmap linear --out $out/textured_cube.png
for m in none linear; do
  "$sim" --obj $data/ground.obj --eye 0,1,0 --target 0,0.7,-5 --far 400 --unlit --mipmap $m \
    --texture-format rgb888 --out "$tmp/ground_$m.png"
done
python3 scripts/side_by_side.py $out/ground_plane.png "$tmp/ground_none.png" "$tmp/ground_linear.png"
rm -rf "$tmp"
echo "docs_images: wrote $out/"
