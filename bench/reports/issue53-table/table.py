"""The Rust/GLSL table of issue 53 item 5 from raw/: run 1 (t1*, sets glsl,rust, places from 0)
and run 2 (t2*, sets rust,glsl, places from 1000), each set alone on 16 fresh devices per
cell. Prints the table, the null controls, and whether run 2's ratio lies in run 1's interval.
    python3 table.py"""
import glob
import json
import os

here = os.path.dirname(os.path.abspath(__file__))


def load(prefix):
    cells = {}
    for path in sorted(glob.glob(os.path.join(here, "raw", prefix + "*", "*", "results.json"))):
        for r in json.load(open(path))["ratios"]:
            iv = r["interval"]
            ratio, low, high = iv["ratio"], iv["low"], iv["high"]
            pair = (r["a"], r["b"])
            key = (r["scene"], r["spp"])
            if pair == ("glsl", "rust"):  # run 1 names GLSL first: Rust/GLSL is its inverse
                cells.setdefault(key, {})["ratio"] = (1 / ratio, 1 / high, 1 / low)
            elif pair == ("rust", "glsl"):
                cells.setdefault(key, {})["ratio"] = (ratio, low, high)
            elif r["null_control"]:
                cells.setdefault(key, {})["null"] = (ratio, low, high)
    return cells


def fmt(c):
    ratio, low, high = c
    half = max(high / ratio - 1, 1 - low / ratio) * 100
    return f"{ratio:.3f} ({low:.3f} to {high:.3f}) ±{half:.1f}%"


one, two = load("t1"), load("t2")
print("| scene | spp | run 1 Rust/GLSL (95% CI) | run 2 Rust/GLSL | run 2 in run 1's | null, run 1 | null, run 2 |")
print("|---|---|---|---|---|---|---|")
inside = within = total = above = nulls = nulls_in = 0
for key in sorted(one, key=lambda k: (k[0].lower(), k[1])):
    a, b = one[key], two.get(key)
    if not b:
        continue
    total += 1
    r2 = b["ratio"][0]
    ok = a["ratio"][1] <= r2 <= a["ratio"][2]
    inside += ok
    for run in (a, b):
        ratio, low, high = run["ratio"]
        within += high / ratio - 1 <= 0.01 and 1 - low / ratio <= 0.01
        above += low > 1.0
        nulls += 1
        nulls_in += run["null"][1] <= 1.0 <= run["null"][2]
    row = [key[0], str(key[1]), fmt(a["ratio"]), fmt(b["ratio"]), "yes" if ok else "no", fmt(a["null"]), fmt(b["null"])]
    print("| " + " | ".join(row) + " |")
print()
print(f"{inside} of {total} cells: run 2's ratio inside run 1's interval")
print(f"{within} of {2 * total} intervals within ±1%; {above} wholly above 1.00")
print(f"{nulls_in} of {nulls} null intervals contain 1")
