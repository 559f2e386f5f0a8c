#!/usr/bin/env bash
# Renders the gallery (README.md, docs/surfaces.md, docs/loop.md, docs/adaptivity.md) into
# docs/gallery/ with the tool itself, every image 1280 pixels wide, then checks that no two
# images are identical. Uses the release binary when built, else the debug one.
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ -x target/release/meshrefine ]]; then
  m=./target/release/meshrefine
else
  cargo build --quiet
  m=./target/debug/meshrefine
fi
out=docs/gallery
mkdir -p "$out"
made=()
# r NAME ARGS...: render docs/gallery/NAME.png at 1280x720 (ARGS may override the size).
r() {
  local name=$1
  shift
  echo "$name"
  $m render "$@" -o "$out/$name.png" --width 1280 --height 720 >/dev/null
  made+=("$out/$name.png")
}
spot=assets/models/spot_control_tri.obj
# The demo's scene: Spot's cage as Loop's limit surface, adaptive at 1 px, the cage over it.
r spot-loop-cage-adaptive "$spot" --surface loop --wireframe cage --pixel-error 1
# The surfaces side by side: one mesh (Spot's 372-triangle cage), one camera.
view=(--pixel-error 0.5 --max-level 32 --eye 1.94,0.965,-1.49 --look-at -0.135,0.028,0.018)
for s in flat phong pn loop; do
  r "spot-$s" "$spot" --surface $s "${view[@]}"
done
# The drivers' refinement: the pattern's lattice, the tessellator's rings, Loop's M1 faces.
r spot-pattern-level4 "$spot" --level 4 --wireframe refined --surface flat
r spot-tess-level4 "$spot" --level 4 --wireframe refined --driver tess --surface flat
r spot-loop-wire "$spot" --level 2 --surface loop --wireframe refined
r spot-phong-wire "$spot" --level 6 --surface phong --wireframe refined
# Displacement: sine and noise on pn, a height map on a grid with texture coordinates.
r spot-pn-sine "$spot" --level 32 --surface pn --displace sine
r spot-pn-noise "$spot" --level 32 --surface pn --displace noise --octaves 3
r grid-pn-heightmap assets/models/grid_uv_8x8.obj --surface pn --displace heightmap --pixel-error 0.5 --max-level 64 --eye 0.4,-1.9,1.9 --look-at 0,-0.1,0
# PN at split normals (a position with several vn): crack-free by default, the papers' crack
# open; close to the rim, on a light background, the crack shows the background through.
rim=(--pixel-error 0.5 --max-level 32 --eye 1.5,1.7,3.0 --look-at 0.3,0.4,1)
for seams in closed open; do
  r "cylinder-pn-$seams" assets/models/cylinder_hard_normals.obj --surface pn --pn-seams $seams --background light "${rim[@]}"
done
# Scalar-tagged PN: the cylinder's rims as creases derived from its hard normals; a tags file
# with a cone-like tip, a fuller vertex and a crease.
r cylinder-stpn assets/models/cylinder_hard_normals.obj --level 8 --surface stpn
r tetrahedron-stpn-tags assets/models/tetrahedron.obj --level 16 --surface stpn --tags assets/examples/tetrahedron.tags
# Loop on a cage (the tetrahedron against flat and pn, one camera) and on an open mesh (sharp
# boundary).
tet=(--pixel-error 0.5 --max-level 32 --eye 3.31,1.28,-2.31 --look-at -0.12,-0.27,0.19)
for s in flat pn loop; do
  r "tetrahedron-$s" assets/models/tetrahedron.obj --surface $s "${tet[@]}"
done
r spot-open-loop assets/models/spot_open.obj --level 8 --surface loop
# Adaptive levels (docs/adaptivity.md): the terrain grazing, Spot close up.
r terrain-levels-grazing assets/models/terrain_16x16.obj --pixel-error 1 --eye 0,0.45,-2.6 --look-at 0,0.1,0 --view levels --wireframe refined
r spot-levels-closeup "$spot" --pixel-error 1 --eye 0.3,0.2,0.6 --look-at 0,0.1,0.3 --view levels --wireframe both
# No two images alike, none left over from earlier versions of this script.
dups=$(sha256sum "${made[@]}" | sort | uniq -w64 -D)
if [[ -n "$dups" ]]; then
  echo "identical images:" >&2
  echo "$dups" >&2
  exit 1
fi
for f in "$out"/*.png; do
  if [[ ! " ${made[*]} " == *" $f "* ]]; then
    echo "$f is not made by this script: remove it or add it here" >&2
    exit 1
  fi
done
du -ch "${made[@]}" | tail -1
