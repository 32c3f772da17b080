#!/usr/bin/env python3
"""Prints, for each run of raw/d1 (HOW-SCENE), each child's first placement and its geometric
mean time per set, so that a child process and a fresh device with the same first placement
sit side by side; and each run's GLSL/Rust interval."""
import glob, json, os

here = os.path.dirname(__file__) or "."
runs = {}
for path in sorted(glob.glob(os.path.join(here, "raw", "d1", "*", "results.json"))):
    r = json.load(open(path))
    name = os.path.basename(os.path.dirname(path))
    rows = {row["set"]: row["placements"] for row in r["rows"]}
    ratio = next(x for x in r["ratios"] if {x["a"], x["b"]} == {"glsl", "rust"})["interval"]
    runs[name] = (rows, ratio)
names = sorted(runs)
for s in ("glsl", "rust"):
    print(f"\n{s}: ms per child, by first placement\n")
    print("| first | " + " | ".join(names) + " |")
    print("|---|" + "---|" * len(names))
    firsts = runs[names[0]][0][s]["first_placement"]
    for k, f in enumerate(firsts):
        cells = []
        for n in names:
            p = runs[n][0][s]
            cells.append(f"{p['median_ms'][p['first_placement'].index(f)]:.3f}" if f in p["first_placement"] else "")
        print(f"| {f} | " + " | ".join(cells) + " |")
print("\n| run | GLSL/Rust (95% CI) |\n|---|---|")
for n in names:
    i = runs[n][1]
    print(f"| {n} | {i['ratio']:.3f} ({i['low']:.3f} to {i['high']:.3f}) |")
