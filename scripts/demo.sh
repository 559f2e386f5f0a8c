#!/usr/bin/env bash
# Sets everything up and runs the demo: a window where a display exists (DISPLAY or
# WAYLAND_DISPLAY), otherwise a headless render of the default scene to meshrefine-view.png.
# Extra arguments go to `meshrefine view` (e.g. --level 32 --wireframe).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh
cargo build --quiet
exec ./target/debug/meshrefine view --wireframe "$@"
