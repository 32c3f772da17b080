#!/usr/bin/env python3
"""One line per `twinray stability --against-world --json` file: the figures of the table in
docs/numerics.md ("The local origin", "Checked against world coordinates").

    python3 summary.py FILE.json [FILE.json ...]
"""
import json
import statistics
import sys


def summary(path):
    rows = json.load(open(path))
    ratios = [r["chosen"]["p99"] / r["world"]["p99"] if r["world"]["p99"] > 0 else 1.0 for r in rows]
    worse = sum(r["worse_rays"] for r in rows)
    grew = sum(1 for x in ratios if x > 1.0)
    return (
        f"{path}: {len(rows)} rows; rays wrong at the chosen origins and right at world {worse}; "
        f"rays wrong chosen {sum(r['chosen']['wrong'] for r in rows)}, world {sum(r['world']['wrong'] for r in rows)}; "
        f"rows whose p99 grew {grew}; largest p99 ratio {max(ratios):.2f}, median {statistics.median(ratios):.2f}; "
        f"rows failing {sum(1 for r in rows if r['failures'])}; "
        f"launches per row {statistics.mean(len(r['launches']) for r in rows):.1f}"
    )


for path in sys.argv[1:]:
    print(summary(path))
