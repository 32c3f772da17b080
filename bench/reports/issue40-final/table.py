#!/usr/bin/env python3
"""The Rust/GLSL table of README.md from raw/t*/ (this pass) and ../inspect-h100/ratios-table-*.csv
(the pass before, the same modules): each cell's ratio with its 95% interval, its null control,
and whether each pass's estimate lies inside the other's interval. Run from this folder."""
import csv, glob, statistics


def cells(paths, first, second, null=False):
    out = {}
    for path in paths:
        for r in csv.DictReader(open(path)):
            if (r["null_control"] == "true") != null or not r["a"].endswith(first) or not r["b"].endswith(second):
                continue
            ratio, lo, hi = float(r["ratio"]), float(r["ci_low"]), float(r["ci_high"])
            # bench writes time(a)/time(b); the table is time(Rust)/time(GLSL).
            out[(r["scene"], int(r["spp"]))] = (ratio, lo, hi) if null else (1 / ratio, 1 / hi, 1 / lo)
    return out


now = cells(glob.glob("raw/t*/*/ratios.csv"), "old/glsl", "old/rust")
nulls = cells(glob.glob("raw/t*/*/ratios.csv"), "old/glsl", "(copy 1)", null=True)
before = cells(glob.glob("../inspect-h100/ratios-table-*.csv"), "glsl", "v192/rust")
inside = 0
print("| scene | spp | Rust/GLSL (95% CI) | null control | pass before | each inside the other's |")
print("|---|---|---|---|---|---|")
for key in sorted(now):
    (r, lo, hi), (nr, nlo, nhi), (p, plo, phi) = now[key], nulls[key], before[key]
    a, b = plo <= r <= phi, lo <= p <= hi
    inside += a + b
    print(f"| {key[0]} | {key[1]} | {r:.3f} ({lo:.3f} to {hi:.3f}) | {nr:.3f} ({nlo:.3f} to {nhi:.3f}) | "
          f"{p:.3f} ({plo:.3f} to {phi:.3f}) | {'yes' if a else 'no'} / {'yes' if b else 'no'} |")
print(f"\nmedian {statistics.median(v[0] for v in now.values()):.3f}; wholly above 1.01: "
      f"{sorted(k for k, v in now.items() if v[1] > 1.01)}; resolved above 1: {sum(v[1] > 1 for v in now.values())}, "
      f"below: {sum(v[2] < 1 for v in now.values())}")
print(f"nulls containing 1: {sum(v[1] <= 1 <= v[2] for v in nulls.values())} of {len(nulls)}; widest "
      f"{max(v[2] - v[1] for v in nulls.values()):.3f}")
print(f"estimates inside the other pass's interval: {inside} of {2 * len(now)}")
