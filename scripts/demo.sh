#!/usr/bin/env bash
# Sets everything up and runs the demo: a window where a display exists (DISPLAY or
# WAYLAND_DISPLAY), otherwise a headless render of the default scene to meshrefine-view.png.
# The scene: Spot's control cage as Loop's limit surface, refined adaptively for a 1-pixel
# bound (levels per element from the camera, crack-free), anti-aliased, with the cage drawn
# over it. Extra arguments go to `meshrefine view` and replace those defaults (e.g.
# --surface pn, --wireframe both, --level 4 instead of the pixel error).
# MESHREFINE_DEMO_PRINT=1 prints the arguments given to `view`, one a line, and does nothing else.
set -euo pipefail
cd "$(dirname "$0")/.."
# Whether the user's arguments (after the first, the options looked for) give one of those
# options (`--opt value` or `--opt=value`; none after `--`).
given() {
    local a opt
    for a in "${@:2}"; do
        [[ $a == -- ]] && return 1
        for opt in $1; do
            [[ $a == "$opt" || $a == "$opt="* ]] && return 0
        done
    done
    return 1
}
defaults=()
given --surface "$@" || defaults+=(--surface loop)
given --wireframe "$@" || defaults+=(--wireframe cage)
given "--pixel-error --level --lod" "$@" || defaults+=(--pixel-error 1)
if [[ ${MESHREFINE_DEMO_PRINT:-} == 1 ]]; then
    printf '%s\n' "${defaults[@]}" "$@"
    exit 0
fi
source scripts/setup.sh
cargo build --quiet
exec ./target/debug/meshrefine view "${defaults[@]}" "$@"
