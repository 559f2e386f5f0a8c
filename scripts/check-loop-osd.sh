#!/usr/bin/env bash
# Compares meshrefine's CPU Loop limit positions (src/subdiv) with OpenSubdiv 3.5's
# (Far::TopologyRefiner with SCHEME_LOOP, PrimvarRefiner::Limit; tools/osd_limit.cpp) on closed
# and open meshes with valences 3 to 24, after 0, 1 and 2 steps, both boundary rules: every limit
# point must agree within 1e-6 of the mesh's bounding-box diagonal (refined vertices are matched
# as point sets: the two number edge points differently). Installs libosd-dev if missing.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/setup.sh >/dev/null
if ! dpkg-query -W -f='${Status}' libosd-dev 2>/dev/null | grep -q "install ok installed"; then
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends libosd-dev >/dev/null
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
g++ -O1 -std=c++14 -o "$work/osd_limit" tools/osd_limit.cpp -losdCPU
cargo build --quiet --example loop_limit
ours=target/debug/examples/loop_limit
fails=0
for mesh in tetrahedron octahedron icosahedron cube_tri torus_16x8 bicone16 uvsphere12 spot_control_tri grid_open_8x8 fan24_open halfdisc17_open spot_open; do
  for steps in 0 1 2; do
    for boundary in edge-only edge-and-corner; do
      m=assets/models/$mesh.obj
      "$ours" "$m" "$steps" "$boundary" --osd-input | "$work/osd_limit" > "$work/osd.txt"
      "$ours" "$m" "$steps" "$boundary" > "$work/ours.txt"
      if ! python3 - "$work/ours.txt" "$work/osd.txt" "$mesh $steps $boundary" <<'PY'
import sys
def load(p):
    return [tuple(map(float, l.split()[1:])) for l in open(p) if l.startswith('v ')]
a, b, what = load(sys.argv[1]), load(sys.argv[2]), sys.argv[3]
if len(a) != len(b):
    sys.exit(f"{what}: {len(a)} limit points against OpenSubdiv's {len(b)}")
lo = [min(p[i] for p in a) for i in range(3)]; hi = [max(p[i] for p in a) for i in range(3)]
diag = sum((h - l) ** 2 for h, l in zip(hi, lo)) ** 0.5
tol = 1e-6 * diag
def key(p): return tuple(round(c / (tol * 10), 0) for c in p)
# Match as point sets: sort both, then check the nearest for each (a grid of cells of 10 tol).
from collections import defaultdict
cells = defaultdict(list)
for q in b: cells[key(q)].append(q)
worst = 0.0
for p in a:
    k = key(p)
    best = min((sum((x - y) ** 2 for x, y in zip(p, q)) ** 0.5
                for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1)
                for q in cells.get((k[0] + dx, k[1] + dy, k[2] + dz), [])), default=float('inf'))
    worst = max(worst, best)
ok = worst <= tol
print(f"{'ok  ' if ok else 'FAIL'} {what}: {len(a)} points, max distance {worst:.3e} (tolerance {tol:.3e})")
sys.exit(0 if ok else 1)
PY
      then fails=$((fails + 1)); fi
    done
  done
done
[ "$fails" -eq 0 ] && echo "OpenSubdiv agrees on every mesh" || { echo "$fails comparisons failed"; exit 1; }
