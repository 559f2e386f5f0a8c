#!/usr/bin/env bash
# Sets everything up and runs the whole test suite: unit tests, GPU tests on lavapipe with the
# validation layer on, the command line, the window demo under Xvfb, formatting and lints.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh
# Tests run on lavapipe unless MESHREFINE_TEST_DEVICE_ANY=1 (then the loader's default devices).
if [ -z "${MESHREFINE_TEST_DEVICE_ANY:-}" ] && [ -f /usr/share/vulkan/icd.d/lvp_icd.x86_64.json ]; then
  export VK_DRIVER_FILES=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json
fi
if cargo fmt --version >/dev/null 2>&1; then cargo fmt --all -- --check; fi
if cargo clippy --version >/dev/null 2>&1; then cargo clippy --all-targets --quiet -- -D warnings; fi
# The library's documentation builds without a warning (broken links, private items).
RUSTDOCFLAGS="-D warnings" cargo doc --no-deps --lib --quiet
# The oldest Rust the README promises (rust-version in Cargo.toml) type-checks every target with
# the locked dependencies, its build in target/msrv (the stable build stays as it is). It needs
# rustup (installing that toolchain once, from the network): without either it is skipped, and
# says so. MESHREFINE_SKIP_MSRV=1 skips it.
msrv=$(sed -n 's/^rust-version *= *"\(.*\)"$/\1/p' Cargo.toml)
if [ -z "$msrv" ]; then
  echo "test: no rust-version in Cargo.toml" >&2
  exit 1
elif [ -n "${MESHREFINE_SKIP_MSRV:-}" ]; then
  echo "test: Rust $msrv (rust-version) not checked: MESHREFINE_SKIP_MSRV is set"
elif ! command -v rustup >/dev/null 2>&1; then
  echo "test: Rust $msrv (rust-version) not checked: no rustup"
elif ! rustup run "$msrv" rustc --version >/dev/null 2>&1 &&
     ! rustup toolchain install "$msrv" --profile minimal; then
  echo "test: Rust $msrv (rust-version) not checked: rustup could not install it (above)"
else
  CARGO_TARGET_DIR=target/msrv rustup run "$msrv" cargo check --all-targets --locked --quiet
fi
log=$(mktemp)
trap 'rm -f "$log"' EXIT
cargo test --all-targets 2>&1 | tee "$log"
# The CPU Loop reference against OpenSubdiv (limit positions, several meshes and steps).
bash scripts/check-loop-osd.sh
# One closing line for the whole suite (cargo prints one per test binary).
awk '/^test result:/ { for (i = 1; i <= NF; i++) { if ($i ~ /^passed;?$/) p += $(i-1); if ($i ~ /^failed;?$/) f += $(i-1) } }
     END { printf "%d passed, %d failed\n", p, f }' "$log"
