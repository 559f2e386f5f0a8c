#!/usr/bin/env bash
# Renders the README's gallery into docs/gallery/ with the tool itself.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --quiet
m=./target/debug/meshrefine
out=docs/gallery
mkdir -p "$out"
$m render -o "$out/spot-pattern-level4.png" --width 640 --height 360 --level 4 --wireframe --surface flat
$m render -o "$out/spot-tess-level4.png" --width 640 --height 360 --level 4 --wireframe --driver tess --surface flat
$m render assets/models/torus_16x8_vn.obj -o "$out/torus-pattern-level3.png" --width 640 --height 360 --level 3 --wireframe --surface flat
# Every surface on the default mesh (level 8), then the displacements on pn.
for s in flat phong pn; do
  $m render -o "$out/spot-$s.png" --width 427 --height 240 --level 8 --surface $s
done
$m render -o "$out/spot-pn-sine.png" --width 427 --height 240 --level 32 --surface pn --displace sine
$m render -o "$out/spot-pn-noise.png" --width 427 --height 240 --level 32 --surface pn --displace noise --octaves 3
$m render -o "$out/spot-phong-wire.png" --width 427 --height 240 --level 6 --surface phong --wireframe
# PN at split normals (a position with several vn): crack-free by default, the papers' crack open.
for seams in closed open; do
  $m render assets/models/cylinder_hard_normals.obj -o "$out/cylinder-pn-$seams.png" --width 427 --height 240 --level 8 --surface pn --pn-seams $seams
  $m render assets/models/cube_face_normals.obj -o "$out/cube-pn-$seams.png" --width 427 --height 240 --level 8 --surface pn --pn-seams $seams
done
# The height map (the generated default) on a mesh with texture coordinates, pn, level 32.
$m render assets/models/grid_uv_8x8.obj -o "$out/grid-pn-heightmap.png" --width 427 --height 240 --level 32 --surface pn --displace heightmap
# Scalar-tagged PN: the cylinder's rims as creases, derived from its hard normals (stpn) against pn.
$m render assets/models/cylinder_hard_normals.obj -o "$out/cylinder-stpn.png" --width 427 --height 240 --level 8 --surface stpn
# Scalar-tagged PN with a tags file: a cone-like tip, a fuller vertex and a crease.
$m render assets/models/tetrahedron.obj -o "$out/tetrahedron-stpn-tags.png" --width 427 --height 240 --level 16 --surface stpn --tags assets/examples/tetrahedron.tags
# Loop subdivision's limit surface (basis function tables) against pn and flat on the same meshes;
# the wireframe shows M1's faces, each refined at level 2; an open mesh (sharp boundary); and the loop surface's normals
# (subdivision shading) on the coarse tetrahedron, flat and pn beside it.
$m render -o "$out/spot-loop.png" --width 427 --height 240 --level 8 --surface loop
$m render -o "$out/spot-loop-wire.png" --width 640 --height 360 --level 2 --surface loop --wireframe
for s in flat pn loop; do
  $m render assets/models/tetrahedron.obj -o "$out/tetrahedron-$s.png" --width 320 --height 240 --level 16 --surface $s
done
$m render assets/models/spot_open.obj -o "$out/spot-open-loop.png" --width 427 --height 240 --level 8 --surface loop
