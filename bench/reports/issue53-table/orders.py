"""Rust/GLSL by the order of a round: for each run folder named, the mean over its cells and
rounds of log(Rust/GLSL) in rounds of each order (C is the null's copy), less the run's mean.
Each order occurs once in every six rounds (`placements.position` in results.json).
    python3 orders.py n1 n2 l1 l2 u1 u2"""
import collections
import glob
import json
import math
import os
import statistics
import sys

here = os.path.dirname(os.path.abspath(__file__))


def by_order(prefix):
    out = collections.defaultdict(list)
    for path in sorted(glob.glob(os.path.join(here, "raw", prefix, "*", "results.json"))):
        rows = {(r["scene"], r["spp"], r["set"]): r["placements"] for r in json.load(open(path))["rows"]}
        for scene, spp in {(k[0], k[1]) for k in rows}:
            sets = [k[2] for k in rows if k[:2] == (scene, spp)]
            copies = [s for s in sets if s not in ("rust", "glsl")]
            if "rust" not in sets or "glsl" not in sets or len(copies) != 1:
                continue
            g, r, c = rows[(scene, spp, "glsl")], rows[(scene, spp, "rust")], rows[(scene, spp, copies[0])]
            for i in range(len(g["median_ms"])):
                order = "".join(x for _, x in sorted([(g["position"][i], "G"), (r["position"][i], "R"), (c["position"][i], "C")]))
                out[order].append(math.log(r["median_ms"][i] / g["median_ms"][i]))
    return out


for prefix in sys.argv[1:]:
    orders = by_order(prefix)
    mean = statistics.mean(x for v in orders.values() for x in v)
    cells = " ".join(f"{o} {(statistics.mean(v) - mean) * 100:+.3f}% ({len(v)})" for o, v in sorted(orders.items()))
    print(f"{prefix}: {cells}")
