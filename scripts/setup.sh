#!/usr/bin/env bash
# Installs everything meshrefine needs on Debian 12 (idempotent): build tools, Debian's shaderc
# (static glslang/SPIRV-Tools archives, linked through .cargo/config.toml), the Vulkan loader,
# lavapipe (Mesa's software Vulkan driver), the validation layer, Xvfb for the window tests, and
# a Rust toolchain if none is installed. Run as root (or with sudo available).
set -euo pipefail

packages=(
  build-essential pkg-config ca-certificates curl
  libshaderc-dev                                   # shaderc + static glslang / SPIRV-Tools
  libvulkan1 mesa-vulkan-drivers                   # Vulkan loader + lavapipe
  vulkan-validationlayers vulkan-tools             # validation layer (on in every GPU test), vulkaninfo
  glslang-tools spirv-tools                        # glslangValidator / spirv-val for shader work
  libosd-dev                                       # OpenSubdiv: the independent Loop reference (scripts/check-loop-osd.sh)
  xvfb xdotool openbox x11-utils libxkbcommon-x11-0 libxcursor1 libxi6 libx11-xcb1 libxrandr2  # window demo under Xvfb; xdotool resizes it, openbox minimises it, xmessage covers it in the tests
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi

if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

if ! command -v cargo >/dev/null 2>&1 && [ -x "$HOME/.cargo/bin/cargo" ]; then
  export PATH="$HOME/.cargo/bin:$PATH"
fi
if ! command -v cargo >/dev/null 2>&1; then
  echo "setup: no Rust toolchain found, installing one with rustup (stable)"
  curl -sSf https://sh.rustup.rs | sh -s -- -y --profile minimal --component clippy,rustfmt
  export PATH="$HOME/.cargo/bin:$PATH"
fi
echo "setup: ready ($(cargo --version))"
