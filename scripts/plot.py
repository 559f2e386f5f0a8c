#!/usr/bin/env python3
"""The benchmark charts, from the CSV files the benchmarks write into docs/bench/. Plain Python 3,
no packages; each chart is an SVG beside its CSV and says in its title which way is better.

    python3 scripts/plot.py            # every chart whose CSV exists
    python3 scripts/plot.py memory     # one of: memory, cost, throughput, adaptive

- memory:     docs/bench/memory.svg     GPU geometry bytes against level, static / pattern / tess,
              on Spot (fig7.csv: the 2005 paper's point, the pattern's memory does not grow
              with coarse triangles x level)
- cost:       docs/bench/fig8.svg       GPU ns per refined triangle against level, every surface
              and driver (fig8.csv: the 2010 paper's Fig. 8)
- throughput: docs/bench/throughput.svg refined triangles per GPU ms against level, pattern
              submissions and tess against static, per mesh (fig7.csv)
- adaptive:   docs/bench/adaptive-{triangles,time}.svg  refined triangles (against the smallest
              uniform level meeting the same bound) and GPU ms (against its next power of two)
              against the pixel error, per scene and driver (adaptive.csv; the pattern driver
              without geomorphing from adaptive-integer.csv)
"""
import csv
import math
import os
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
BENCH = os.path.join(ROOT, "docs", "bench")

# Colour per series key part, dash per driver: every line stays visible where two coincide
# (markers differ too, and coinciding lines are drawn thinner on top).
PALETTE = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf",
           "#7f7f7f", "#bcbd22"]
DASHES = {"static": "", "pattern/instanced": "", "pattern/push": "2,3", "pattern/ubo": "8,3,2,3",
          "tess": "7,4", "adaptive": "", "uniform": "7,4"}
MARKERS = ["circle", "square", "diamond", "triangle", "cross"]


def read(name):
    path = os.path.join(BENCH, name)
    if not os.path.exists(path):
        return None
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def esc(s):
    return s.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def marker(kind, x, y, color):
    r = 3.5
    if kind == "circle":
        return f'<circle cx="{x:.1f}" cy="{y:.1f}" r="{r}" fill="{color}"/>'
    if kind == "square":
        return f'<rect x="{x-r:.1f}" y="{y-r:.1f}" width="{2*r}" height="{2*r}" fill="{color}"/>'
    if kind == "diamond":
        return (f'<polygon points="{x:.1f},{y-r-1:.1f} {x+r+1:.1f},{y:.1f} {x:.1f},{y+r+1:.1f} '
                f'{x-r-1:.1f},{y:.1f}" fill="{color}"/>')
    if kind == "triangle":
        return (f'<polygon points="{x:.1f},{y-r-1:.1f} {x+r+1:.1f},{y+r:.1f} {x-r-1:.1f},{y+r:.1f}" '
                f'fill="{color}"/>')
    return (f'<path d="M{x-r:.1f},{y-r:.1f}L{x+r:.1f},{y+r:.1f}M{x-r:.1f},{y+r:.1f}L{x+r:.1f},{y-r:.1f}" '
            f'stroke="{color}" stroke-width="2"/>')


def chart(path, title, better, subtitle, xlabel, ylabel, series, xlog=True, ylog=True, xticks=None):
    """series: list of (label, color, dash, marker, [(x, y)]). Log axes by default."""
    W, H, L, R, T, B = 920, 500, 80, 300, 64, 52
    pts = [p for s in series for p in s[4] if p[1] > 0 or not ylog]
    xs = [p[0] for p in pts]
    ys = [p[1] for p in pts]
    fx = (lambda v: math.log10(v)) if xlog else (lambda v: v)
    fy = (lambda v: math.log10(v)) if ylog else (lambda v: v)
    x0, x1 = fx(min(xs)), fx(max(xs))
    if ylog:
        y0, y1 = math.floor(math.log10(min(ys))), math.ceil(math.log10(max(ys)))
    else:
        y0, y1 = 0.0, max(ys) * 1.08
    sx = lambda v: L + (fx(v) - x0) / max(x1 - x0, 1e-9) * (W - L - R)
    sy = lambda v: T + (1 - (fy(v) - y0) / max(y1 - y0, 1e-9)) * (H - T - B)
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" '
           f'font-family="sans-serif" font-size="12">',
           f'<rect width="{W}" height="{H}" fill="white"/>',
           f'<text x="{L}" y="20" font-size="15" font-weight="bold">{esc(title)}</text>',
           f'<text x="{L}" y="38" fill="#333">{esc(better)}</text>',
           f'<text x="{L}" y="54" fill="#777" font-size="11">{esc(subtitle)}</text>',
           f'<line x1="{L}" y1="{H-B}" x2="{W-R}" y2="{H-B}" stroke="black"/>',
           f'<line x1="{L}" y1="{T}" x2="{L}" y2="{H-B}" stroke="black"/>']
    for v in (xticks or sorted(set(xs))):
        out.append(f'<text x="{sx(v):.1f}" y="{H-B+18}" text-anchor="middle">{v:g}</text>')
    out.append(f'<text x="{(L+W-R)/2:.1f}" y="{H-10}" text-anchor="middle">{esc(xlabel)}</text>')
    if ylog:
        for e in range(y0, y1 + 1):
            for m in (1, 2, 5):
                v = m * 10 ** e
                if v > 10 ** y1:
                    break
                label = f"{v:g}" if m == 1 else ""
                out.append(f'<text x="{L-8}" y="{sy(v)+4:.1f}" text-anchor="end">{label}</text>')
                out.append(f'<line x1="{L}" y1="{sy(v):.1f}" x2="{W-R}" y2="{sy(v):.1f}" stroke="#eee"/>')
    else:
        for i in range(6):
            v = y1 * i / 5
            out.append(f'<text x="{L-8}" y="{sy(v)+4:.1f}" text-anchor="end">{v:.3g}</text>')
            out.append(f'<line x1="{L}" y1="{sy(v):.1f}" x2="{W-R}" y2="{sy(v):.1f}" stroke="#eee"/>')
    mid = (T + H - B) / 2
    out.append(f'<text x="16" y="{mid:.1f}" transform="rotate(-90 16 {mid:.1f})" '
               f'text-anchor="middle">{esc(ylabel)}</text>')
    for i, (label, color, dash, mk, data) in enumerate(series):
        data = sorted(p for p in data if p[1] > 0 or not ylog)
        if not data:
            continue
        d = f' stroke-dasharray="{dash}"' if dash else ""
        line = " ".join(f"{sx(a):.1f},{sy(b):.1f}" for a, b in data)
        # Later series thinner: a line drawn over an equal one leaves the first visible.
        width = max(3.5 - 0.5 * i, 1.2)
        out.append(f'<polyline points="{line}" fill="none" stroke="{color}" '
                   f'stroke-width="{width:.1f}"{d} opacity="0.9"/>')
        for a, b in data:
            out.append(marker(mk, sx(a), sy(b), color))
        ly = T + 8 + 18 * i
        out.append(f'<line x1="{W-R+12}" y1="{ly}" x2="{W-R+44}" y2="{ly}" stroke="{color}" '
                   f'stroke-width="2"{d}/>')
        out.append(marker(mk, W - R + 28, ly, color))
        out.append(f'<text x="{W-R+50}" y="{ly+4}">{esc(label)}</text>')
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")
    print(f"wrote {os.path.relpath(path, ROOT)}")


def device_of(rows):
    return rows[0]["device"] if rows else ""


def variants_in(rows):
    order = ["static", "pattern/push", "pattern/ubo", "pattern/instanced", "tess"]
    found = {r["variant"] for r in rows}
    return [v for v in order if v in found] + sorted(found - set(order))


def memory():
    rows = read("fig7.csv")
    if not rows:
        return
    rows = [r for r in rows if r["mesh"] == "spot" and r["geometry_bytes"]]
    series = []
    # The pattern's submissions store the same bytes: one line for them.
    for i, (label, v) in enumerate((("static", "static"), ("pattern (every submission)",
                                    "pattern/instanced"), ("tess", "tess"))):
        data = [(int(r["level"]), int(r["geometry_bytes"])) for r in rows if r["variant"] == v]
        series.append((label, PALETTE[i], DASHES.get(v, ""), MARKERS[i], data))
    chart(os.path.join(BENCH, "memory.svg"),
          "GPU geometry memory against level (Spot, 372 coarse triangles)",
          "Lower is better: static stores every refined vertex; the pattern stores one pattern "
          "and the records; tess stores the records.",
          device_of(rows) + " — cargo bench --bench fig7",
          "level N (segments per coarse edge)", "GPU geometry bytes (log)", series)


def cost():
    rows = read("fig8.csv")
    if not rows:
        return
    rows = [r for r in rows if r["gpu_ns_per_refined_triangle"]]
    surfaces = sorted({r["surface"] for r in rows}, key=["flat", "phong", "pn", "stpn", "loop"].index)
    series = []
    for i, s in enumerate(surfaces):
        for j, v in enumerate(variants_in([r for r in rows if r["surface"] == s])):
            data = [(int(r["level"]), float(r["gpu_ns_per_refined_triangle"]))
                    for r in rows if r["surface"] == s and r["variant"] == v]
            series.append((f"{s} {v}", PALETTE[i], DASHES.get(v, ""), MARKERS[j % 5], data))
    chart(os.path.join(BENCH, "fig8.svg"),
          "GPU time per refined triangle against level (Spot; Fig. 8 of Holländer & Boubekeur)",
          "Lower is better: the per-element overhead is paid off as the level grows.",
          device_of(rows) + " — cargo bench --bench table1",
          "level N (segments per element edge)", "GPU ns per refined triangle (log)", series)


def throughput():
    rows = read("fig7.csv")
    if not rows:
        return
    rows = [r for r in rows if r["gpu_ms_median"]]
    meshes = sorted({r["mesh"] for r in rows}, key=lambda m: int(next(
        r["coarse_triangles"] for r in rows if r["mesh"] == m)))
    series = []
    for i, m in enumerate(meshes):
        coarse = next(r["coarse_triangles"] for r in rows if r["mesh"] == m)
        static = {r["level"]: float(r["gpu_ms_median"]) for r in rows
                  if r["mesh"] == m and r["variant"] == "static"}
        for j, v in enumerate(("pattern/instanced", "tess")):
            # Triangles per ms against static's at the same mesh and level: the static
            # buffer's time over the variant's, scaled by the triangles each made.
            tris = {r["level"]: int(r["refined_triangles"]) for r in rows
                    if r["mesh"] == m and r["variant"] == "static"}
            data = [(int(r["level"]), static[r["level"]] / float(r["gpu_ms_median"])
                     * int(r["refined_triangles"]) / tris[r["level"]])
                    for r in rows if r["mesh"] == m and r["variant"] == v and r["level"] in static]
            series.append((f"{m} ({coarse} tris) {v}", PALETTE[i], DASHES.get(v, ""), MARKERS[j], data))
    chart(os.path.join(BENCH, "throughput.svg"),
          "Throughput against the static buffer's (refined triangles per GPU ms, same mesh and level)",
          "Higher is better; 1 is the static buffer's speed, which the pattern reaches without its memory.",
          device_of(rows) + " — cargo bench --bench fig7",
          "level N (segments per coarse edge)", "throughput / static's", series, ylog=False)


def adaptive():
    rows = read("adaptive.csv")
    if not rows:
        return
    # The pattern driver without geomorphing (integer levels): its adaptive rows beside the
    # others (its uniform rows are the geomorphing run's uniform frames again).
    for r in read("adaptive-integer.csv") or []:
        if r["adaptive"] == "true":
            r["variant"] += ", geomorph off"
            rows.append(r)
    rows = [r for r in rows if r["gpu_ms_median"]]
    keys = sorted({(r["scene"], r["variant"]) for r in rows})
    # Triangles against the smallest uniform level meeting the bound; GPU time against the
    # smallest power of two at or above it (the targets of docs/benchmarks.md).
    for what, col, ylabel, reference in (
            ("triangles", "refined_triangles", "refined triangles (log)", "bound"),
            ("time", "gpu_ms_median", "GPU ms per frame (log)", "pow2")):
        series = []
        for i, (scene, variant) in enumerate(keys):
            for j, mode in enumerate(("adaptive", "uniform")):
                if mode == "uniform" and variant.endswith("geomorph off"):
                    continue
                data = [(float(r["pixel_error"]), float(r[col])) for r in rows
                        if r["scene"] == scene and r["variant"] == variant and r[col]
                        and (r["adaptive"] == "true" if mode == "adaptive"
                             else reference in r["level_from"].split("+"))]
                label = mode if mode == "adaptive" else f"uniform ({reference})"
                series.append((f"{scene} {variant} {label}", PALETTE[i % len(PALETTE)],
                               DASHES[mode], MARKERS[j], sorted(data)))
        chart(os.path.join(BENCH, f"adaptive-{what}.svg"),
              f"Adaptive against uniform refinement: {what} against the pixel error",
              "Lower is better: adaptive levels meet the same pixel bound as the uniform level "
              f"({'the smallest' if reference == 'bound' else 'the next power of two of the smallest'}"
              " that does).",
              device_of(rows) + " — cargo bench --bench adaptive", "pixel error bound (px)", ylabel,
              series, xticks=sorted({float(r["pixel_error"]) for r in rows}))


CHARTS = {"memory": memory, "cost": cost, "throughput": throughput, "adaptive": adaptive}

if __name__ == "__main__":
    names = sys.argv[1:] or list(CHARTS)
    for n in names:
        if n not in CHARTS:
            sys.exit(f"plot.py: no chart named {n!r} (one of: {', '.join(CHARTS)})")
        CHARTS[n]()
