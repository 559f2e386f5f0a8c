#!/usr/bin/env python3
"""Per-triangle cost against level (the 2010 paper's Fig. 8) from docs/bench/fig8.csv, written
by `cargo bench --bench table1`: one line per surface and driver, GPU nanoseconds per refined
triangle against the level (log scales). Writes docs/bench/fig8.svg. Plain Python 3, no packages."""
import csv
import math
import os
import sys

root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
src = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "docs/bench/fig8.csv")
dst = sys.argv[2] if len(sys.argv) > 2 else os.path.join(root, "docs/bench/fig8.svg")

series = {}
device = ""
with open(src, newline="") as f:
    for r in csv.DictReader(f):
        if not r["gpu_ns_per_refined_triangle"]:
            continue
        device = r["device"]
        key = (r["surface"], r["variant"])
        series.setdefault(key, []).append((int(r["level"]), float(r["gpu_ns_per_refined_triangle"])))

W, H, L, R, T, B = 760, 460, 70, 190, 50, 50
levels = sorted({l for s in series.values() for l, _ in s})
costs = [c for s in series.values() for _, c in s]
lo, hi = math.log2(min(levels)), math.log2(max(levels))
# Log scale on both axes: the cost per triangle falls by orders of magnitude with the level.
ylo = math.floor(math.log10(min(costs)))
yhi = math.ceil(math.log10(max(costs)))
def x(l):
    return L + (math.log2(l) - lo) / max(hi - lo, 1e-9) * (W - L - R)
def y(c):
    return T + (1 - (math.log10(c) - ylo) / max(yhi - ylo, 1e-9)) * (H - T - B)

colors = {"flat": "#888888", "phong": "#2f7ed8", "pn": "#8bbc21", "stpn": "#910000", "loop": "#e06000"}
out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">',
       f'<rect width="{W}" height="{H}" fill="white"/>',
       f'<text x="{L}" y="20" font-size="14">GPU ns per refined triangle against level (Fig. 8 of Holländer &amp; Boubekeur 2010)</text>',
       f'<text x="{L}" y="36" fill="#555">{device}</text>',
       f'<line x1="{L}" y1="{H-B}" x2="{W-R}" y2="{H-B}" stroke="black"/>',
       f'<line x1="{L}" y1="{T}" x2="{L}" y2="{H-B}" stroke="black"/>']
for l in levels:
    out.append(f'<text x="{x(l):.1f}" y="{H-B+18}" text-anchor="middle">{l}</text>')
out.append(f'<text x="{(L+W-R)/2:.1f}" y="{H-12}" text-anchor="middle">level N (segments per element edge)</text>')
for e in range(ylo, yhi + 1):
    for m in (1, 2, 5):
        c = m * 10 ** e
        if c > 10 ** yhi:
            break
        label = f"{c:g}" if m == 1 else ""
        out.append(f'<text x="{L-8}" y="{y(c)+4:.1f}" text-anchor="end">{label}</text>')
        out.append(f'<line x1="{L}" y1="{y(c):.1f}" x2="{W-R}" y2="{y(c):.1f}" stroke="#eee"/>')
out.append(f'<text x="16" y="{(T+H-B)/2:.1f}" transform="rotate(-90 16 {(T+H-B)/2:.1f})" text-anchor="middle">GPU ns per refined triangle (log)</text>')
for i, ((surface, variant), pts) in enumerate(sorted(series.items())):
    pts.sort()
    color = colors.get(surface, "black")
    dash = ' stroke-dasharray="6,4"' if variant == "tess" else ""
    path = " ".join(f"{x(l):.1f},{y(c):.1f}" for l, c in pts)
    out.append(f'<polyline points="{path}" fill="none" stroke="{color}" stroke-width="2"{dash}/>')
    ly = T + 10 + 18 * i
    out.append(f'<line x1="{W-R+10}" y1="{ly}" x2="{W-R+40}" y2="{ly}" stroke="{color}" stroke-width="2"{dash}/>')
    out.append(f'<text x="{W-R+46}" y="{ly+4}">{surface} {variant}</text>')
out.append("</svg>")
with open(dst, "w") as f:
    f.write("\n".join(out) + "\n")
print(f"wrote {dst}")
