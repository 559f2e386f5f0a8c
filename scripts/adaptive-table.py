#!/usr/bin/env python3
"""The table of docs/benchmarks.md's "Adaptive refinement", from the CSV files
`cargo bench --bench adaptive` writes (docs/bench/adaptive.csv, and adaptive-integer.csv for the
pattern driver without geomorphing). Plain Python 3, no packages; prints Markdown.

    python3 scripts/adaptive-table.py

Each adaptive row against the uniform rows of the same scene, driver and pixel error in the same
run: `bound` (the smallest uniform level meeting the bound) and `pow2` (the power of two at or
above it; one row, `bound+pow2`, where they are the same level). The level pass's share is its time over its time plus the frame's GPU time.
"""
import csv
import os

BENCH = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs", "bench")
SCENES = ["close-up", "grazing", "flythrough"]
# (label, file, variant) in the table's order within one scene and pixel error.
DRIVERS = [
    ("static", "adaptive.csv", "static"),
    ("pattern/instanced", "adaptive.csv", "pattern/instanced"),
    ("pattern/instanced, geomorph off", "adaptive-integer.csv", "pattern/instanced"),
    ("tess", "adaptive.csv", "tess"),
]


def rows(name):
    with open(os.path.join(BENCH, name), newline="") as f:
        return list(csv.DictReader(f))


def number(x):
    return f"{int(x):,}"


def main():
    files = {name: rows(name) for name in {d[1] for d in DRIVERS}}
    print("| scene | driver | px | adaptive tris | bound level | tris / bound's | GPU ms adaptive "
          "| GPU / bound's | GPU / pow2's | level pass ms (GPU) | level pass share "
          "| CPU refine ms | uploaded bytes |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    pixel_errors = sorted({float(r["pixel_error"]) for r in files["adaptive.csv"]})
    for scene in SCENES:
        for px in pixel_errors:
            for label, name, variant in DRIVERS:
                def find(source):
                    found = [r for r in files[name]
                             if r["scene"] == scene and r["variant"] == variant
                             and float(r["pixel_error"]) == px
                             and source in r["level_from"].split("+")]
                    return found[0] if found else None
                a, b, p = find("view"), find("bound"), find("pow2")
                if a is None or b is None or p is None:
                    continue
                tris = float(a["refined_triangles"])
                gpu = float(a["gpu_ms_median"])
                lp = float(a["level_pass_ms"])
                cpu = a["cpu_ms"]
                upload = a["upload_bytes"]
                print(f"| {scene} | {label} | {px:g} | {number(tris)} | {b['level']} "
                      f"| {tris / float(b['refined_triangles']):.2f}x | {gpu:.0f} "
                      f"| {gpu / float(b['gpu_ms_median']):.2f}x "
                      f"| {gpu / float(p['gpu_ms_median']):.2f}x | {lp:.2f} "
                      f"| {100 * lp / (lp + gpu):.1f} % "
                      f"| {f'{float(cpu):.1f}' if cpu else '–'} "
                      f"| {number(float(upload)) if upload else '–'} |")


if __name__ == "__main__":
    main()
