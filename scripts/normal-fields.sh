#!/usr/bin/env bash
# Renders the normal-field comparison of docs/surfaces.md into docs/images/ with the tool itself:
# pn with each --normal-field on a dense mesh with computed normals, on a control cage and on a
# mesh with hard edges.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --quiet
m=./target/debug/meshrefine
out=docs/images
mkdir -p "$out"
for f in paper vlachos linear; do
  $m render assets/models/spot_tri.obj -o "$out/spot-dense-$f.png" --width 640 --height 480 --level 2 --surface pn --normal-field $f
  $m render assets/models/spot_control_tri.obj -o "$out/spot-cage-$f.png" --width 427 --height 320 --level 8 --surface pn --normal-field $f
  $m render assets/models/cylinder_hard_normals.obj -o "$out/cylinder-$f.png" --width 427 --height 320 --level 8 --surface pn --normal-field $f
done
