#!/usr/bin/env bash
# Renders the README's gallery into docs/gallery/ with the tool itself.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --quiet
m=./target/debug/meshrefine
out=docs/gallery
mkdir -p "$out"
$m render -o "$out/spot-pattern-level4.png" --width 640 --height 360 --level 4 --wireframe
$m render -o "$out/spot-tess-level4.png" --width 640 --height 360 --level 4 --wireframe --driver tess
$m render assets/models/torus_16x8_vn.obj -o "$out/torus-pattern-level3.png" --width 640 --height 360 --level 3 --wireframe
