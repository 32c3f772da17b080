#!/usr/bin/env python3
"""Prints, per run of raw/b1 (BALLAST-FIRST-SCENE), the GLSL/Rust ratio with its interval and
each set's median time over the first and second halves of its places (drift within a run)."""
import glob, json, os, statistics as st

here = os.path.dirname(__file__) or "."
print("| ballast | first | scene | GLSL/Rust (95% CI) | GLSL ms, 1st half / 2nd half | Rust ms, 1st / 2nd half |")
print("|---|---|---|---|---|---|")
for d in sorted(glob.glob(os.path.join(here, "raw", "b1", "*-*-*")), key=lambda p: [int(x) if x.isdigit() else x for x in os.path.basename(p).split("-")]):
    ballast, first, scene = os.path.basename(d).split("-")
    r = json.load(open(os.path.join(d, "results.json")))
    rows = {row["set"]: row["placements"]["median_ms"] for row in r["rows"]}
    ratio = next(x for x in r["ratios"] if {x["a"], x["b"]} == {"glsl", "rust"})
    i = ratio["interval"]
    flip = ratio["a"] != "glsl"
    v, lo, hi = (1 / i["ratio"], 1 / i["high"], 1 / i["low"]) if flip else (i["ratio"], i["low"], i["high"])
    def halves(ms):
        n = len(ms) // 2
        return f"{st.median(ms[:n]):.3f} / {st.median(ms[n:]):.3f}"
    print(f"| {ballast} | {first} | {scene} | {v:.3f} ({lo:.3f} to {hi:.3f}) | {halves(rows['glsl'])} | {halves(rows['rust'])} |")
