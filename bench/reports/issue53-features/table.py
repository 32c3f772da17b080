#!/usr/bin/env python3
"""Prints the tables of this report from raw/ (the results.json of each bench run)."""
import glob, json, os

W, O = "target/without-textures/", "target/old-sets/"
PAIRS = [
    ("rust", W + "rust", "Rust: specialised / without texture code"),
    ("glsl", W + "glsl", "GLSL: specialised / without texture code"),
    ("rust", O + "rust", "Rust: specialised / e7ee105 (no feature constant)"),
    ("glsl", O + "glsl", "GLSL: specialised / e7ee105"),
    ("rust", "glsl", "Rust / GLSL, specialised"),
    (O + "rust", O + "glsl", "Rust / GLSL at e7ee105"),
]

def oriented(r, a, b):
    """The interval of r as a / b (r may hold b / a)."""
    i = r["interval"]
    if (r["a"], r["b"]) == (a, b):
        return i["ratio"], i["low"], i["high"]
    return 1 / i["ratio"], 1 / i["high"], 1 / i["low"]


def cell(ratio, low, high):
    return f"{ratio:.3f} ({low:.3f} to {high:.3f})"

for run in sorted(glob.glob(os.path.join(os.path.dirname(__file__) or ".", "raw", "*"))):
    ratios = []
    for path in sorted(glob.glob(os.path.join(run, "*", "results.json"))):
        ratios += json.load(open(path))["ratios"]
    if not ratios:
        continue
    print(f"## {os.path.basename(run)}\n")
    for a, b, title in PAIRS:
        rows = [r for r in ratios if {r["a"], r["b"]} == {a, b}]
        if not rows:
            continue
        print(f"### {title}\n\n| scene | spp | ratio (95% CI) | places |\n|---|---|---|---|")
        inside = 0
        for r in rows:
            ratio, low, high = oriented(r, a, b)
            inside += max(ratio - low, high - ratio) <= 0.01 + 1e-9
            print(f"| {r['scene']} | {r['spp']} | {cell(ratio, low, high)} | {r['interval']['placements']} |")
        print(f"\n{inside} of {len(rows)} intervals within ±1%.\n")

# Whether each cell of a later run lies inside the first run's interval.
runs = sorted(glob.glob(os.path.join(os.path.dirname(__file__) or ".", "raw", "*")))
def load(run):
    out = []
    for path in sorted(glob.glob(os.path.join(run, "*", "results.json"))):
        out += json.load(open(path))["ratios"]
    return out
if len(runs) > 1:
    first, later = load(runs[0]), load(runs[1])
    print(f"## {os.path.basename(runs[1])} against {os.path.basename(runs[0])}\n")
    for a, b, title in PAIRS:
        pairs = [(r, s) for r in first for s in later
                 if {r["a"], r["b"]} == {a, b} == {s["a"], s["b"]} and (r["scene"], r["spp"]) == (s["scene"], s["spp"])]
        if pairs:
            inside = sum(1 for r, s in pairs if oriented(r, a, b)[1] <= oriented(s, a, b)[0] <= oriented(r, a, b)[2])
            print(f"- {title}: {inside} of {len(pairs)} cells inside the first run's interval")
