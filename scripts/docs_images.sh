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
# Flat, Gouraud, Phong exact, Phong from a 32-cell lighting table on the coarse sphere.
ball=(--obj $data/sphere.obj --diffuse 0.75,0.35,0.2 --specular 0.8,0.8,0.8 --shininess 60
  --light dir:1,1,1.2 --light dir:-1,0.2,0.4:0.2,0.25,0.4 --global-ambient 0.05,0.05,0.05
  --width 240 --height 180 --eye 0,0,2.6)
for s in flat gouraud phong; do
  "$sim" "${ball[@]}" --shading $s --out "$tmp/$s.png"
done
"$sim" "${ball[@]}" --shading phong --lighting table --lighting-table 32 --out "$tmp/table.png"
python3 scripts/side_by_side.py $out/shading.png "$tmp/flat.png" "$tmp/gouraud.png" "$tmp/phong.png" "$tmp/table.png"
# A sphere environment map on the knot, a normal map of rivets on the sphere.
"$sim" --obj $data/torus_knot.obj --fit --ambient 0.3,0.3,0.3 --diffuse 0.9,0.9,0.9 \
  --specular 0.8,0.8,0.8 --shininess 80 --shading phong --envmap $data/envmap.png \
  --texture-format rgb888 --width 240 --height 180 --out "$tmp/env.png"
"$sim" --obj $data/sphere.obj --diffuse 0.6,0.6,0.65 --specular 0.7,0.7,0.7 --shininess 40 \
  --light dir:1,1,1.2 --shading phong --normalmap $data/bumps.png --width 240 --height 180 \
  --eye 0,0,2.6 --out "$tmp/bumps.png"
python3 scripts/side_by_side.py $out/maps.png "$tmp/env.png" "$tmp/bumps.png"
"$sim" --obj $data/cube.obj --eye 2.2,1.8,3 --texture $data/tiles64.png --diffuse 0.9,0.9,0.9 \
  --specular 0.6,0.6,0.6 --shininess 40 --mipmap linear --out $out/textured_cube.png
for m in none linear; do
  "$sim" --obj $data/ground.obj --eye 0,1,0 --target 0,0.7,-5 --far 400 --unlit --mipmap $m \
    --texture-format rgb888 --out "$tmp/ground_$m.png"
done
python3 scripts/side_by_side.py $out/ground_plane.png "$tmp/ground_none.png" "$tmp/ground_linear.png"
rm -rf "$tmp"
echo "docs_images: wrote $out/"
