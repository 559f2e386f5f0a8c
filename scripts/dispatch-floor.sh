#!/usr/bin/env bash
# What the level pass costs beyond running a dispatch at all: times the pass of the release
# build against the same build with levels.comp's `main` returning at once (an empty shader,
# the same dispatches, barriers and timestamps), alternated, three rounds, on the 16x16 terrain
# seen from low over its edge, pattern (instanced) and tess, gliding and integer levels, 1 and
# 4 px, and prints each configuration's `level_pass_ms` per round (docs/bench/dispatch-floor.md).
# Builds both binaries (the empty one from a temporary edit of glsl/lod/levels.comp, undone
# before it returns) and leaves the release build as it found the sources.
set -euo pipefail
cd "$(dirname "$0")/.."
out=$(mktemp -d)
shader=glsl/lod/levels.comp
cargo build --release --quiet
cp target/release/meshrefine "$out/full"
cp "$shader" "$out/levels.comp"
trap 'cp "$out/levels.comp" "$shader"' EXIT
sed -i 's/    if (i >= view.count) {/    if (i < view.count + 100000000u) {/' "$shader"
grep -q 'view.count + 100000000u' "$shader"
cargo build --release --quiet
cp target/release/meshrefine "$out/empty"
cp "$out/levels.comp" "$shader"
cargo build --release --quiet
for round in 1 2 3; do
  for bin in full empty; do
    for geomorph in on off; do
      for px in 1 4; do
        "$out/$bin" bench assets/models/terrain_16x16.obj --surfaces pn --drivers pattern,tess \
          --pixel-error "$px" --geomorph "$geomorph" --eye=-1.6,0.35,2.2 --look-at=1.2,0.05,-2.0 \
          --frames 20 --levels 1 --out "$out/$bin-$geomorph-$px-$round" > /dev/null
      done
    done
  done
done
python3 - "$out" <<'EOF'
import collections, csv, glob, os, sys
times = collections.defaultdict(list)
for f in sorted(glob.glob(os.path.join(sys.argv[1], "*.csv"))):
    binary, geomorph, px, _ = os.path.basename(f)[:-4].split("-")
    for r in csv.DictReader(open(f)):
        if r["adaptive"] == "true" and r["variant"] in ("pattern/instanced", "tess"):
            times[(r["variant"], geomorph, px, binary)].append(r["level_pass_ms"])
            device = r["device"]
print(f"device: {device}")
print("| driver | geomorph | px | shader | level pass ms, rounds 1-3 |")
print("|---|---|---:|---|---|")
for (variant, geomorph, px, binary), ms in sorted(times.items()):
    print(f"| {variant} | {geomorph} | {px} | {binary} | {' / '.join(ms)} |")
EOF
