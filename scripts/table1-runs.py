#!/usr/bin/env python3
"""Loop's throughput against flat at level 32 across several Table I runs (`cargo bench --bench
table1` writes docs/bench/table1.csv; earlier runs kept in table1.md under "Runs compared"): every mesh and
driver, each run's ratio and their median.

    python3 scripts/table1-runs.py docs/bench/table1.csv OTHER-RUN.csv ...
"""
import csv
import statistics
import sys

LEVEL = "32"


def main(paths):
    cells = {}
    for path in paths:
        with open(path) as f:
            for r in csv.DictReader(f):
                if r["surface"] == "loop" and r["level"] == LEVEL and r["displace"] == "none":
                    ratio = r["throughput_vs_flat"]
                    if ratio:
                        cells.setdefault((r["mesh"], r["variant"]), []).append(float(ratio))
    print(f"| mesh | driver | loop throughput / flat at level {LEVEL}, each run | median |")
    print("|---|---|---|---:|")
    for (mesh, variant), ratios in cells.items():
        each = ", ".join(f"{x:.2f}" for x in ratios)
        print(f"| {mesh} | {variant} | {each} | {statistics.median(ratios):.2f} |")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
