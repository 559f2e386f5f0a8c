#!/usr/bin/env bash
# Sets everything up and runs the demo: a window where a display exists (DISPLAY or
# WAYLAND_DISPLAY), otherwise a headless render of the default scene to meshrefine-view.png.
# The scene: Spot's control cage as Loop's limit surface, refined adaptively for a 1-pixel
# bound (levels per element from the camera, crack-free), anti-aliased, with the cage drawn
# over it. Extra arguments go to `meshrefine view` (e.g. --surface pn, --wireframe both).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh
cargo build --quiet
exec ./target/debug/meshrefine view --surface loop --wireframe cage --pixel-error 1 "$@"
