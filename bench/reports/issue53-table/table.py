"""The Rust/GLSL table of issue 53 item 5 from raw/: run 1 (sets glsl,rust, places from 0) and
run 2 (sets rust,glsl, places from 1000), each set alone on fresh devices, one per cell and
round. Prints the table, the null controls, and whether run 2's ratio lies in run 1's interval.
    python3 table.py            # u1 and u2: the fourth session's runs, 6 rounds, every place spaced
    python3 table.py t1 t2      # the third session's runs, 16 rounds
    python3 table.py p1+s1 p2+s2  # a run with some scenes retimed: s1's cells replace p1's
    python3 table.py l1 l2      # the thirteenth session's, a layout drawn per place
    python3 table.py m2 m1      # ClearCoat alone, 24 rounds (m2 has run 1's label order)
    python3 table.py y1 y2      # the seventeenth session's (run 2's last 8 scenes: the eighteenth's)
    python3 table.py y1 y3      # run 3 (the eighteenth session's, places from 2000) against run 1
    python3 table.py y2 y3      # and against run 2 (the columns still say run 1 and run 2)
A cell that only run 1 has is listed after the table, with its own counts."""
import glob
import json
import math
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))


def load(prefix):
    cells = {}
    for path in sorted(glob.glob(os.path.join(here, "raw", prefix + "*", "*", "results.json"))):
        for r in json.load(open(path))["ratios"]:
            iv = r["interval"]
            ratio, low, high = iv["ratio"], iv["low"], iv["high"]
            se = iv["log_sd"] / math.sqrt(iv["placements"])
            pair = (r["a"], r["b"])
            key = (r["scene"], r["spp"])
            if pair == ("glsl", "rust"):  # run 1 names GLSL first: Rust/GLSL is its inverse
                cells.setdefault(key, {})["ratio"] = (1 / ratio, 1 / high, 1 / low)
                cells[key]["se"] = (se, iv["placements"])
            elif pair == ("rust", "glsl"):
                cells.setdefault(key, {})["ratio"] = (ratio, low, high)
                cells[key]["se"] = (se, iv["placements"])
            elif r["null_control"]:
                cells.setdefault(key, {})["null"] = (ratio, low, high)
    return cells


def fmt(c):
    ratio, low, high = c
    half = max(high / ratio - 1, 1 - low / ratio) * 100
    return f"{ratio:.3f} ({low:.3f} to {high:.3f}) ±{half:.1f}%"


def layered(name):
    """A run's cells, from folders joined by `+`: a later folder's scenes replace an earlier's."""
    cells = {}
    for prefix in name.split("+"):
        cells.update(load(prefix))
    return cells


first, second = (sys.argv[1], sys.argv[2]) if len(sys.argv) > 2 else ("u1", "u2")
one, two = layered(first), layered(second)
# Two-sided 97.5% points of Student's t, by degrees of freedom.
T975 = {5: 2.571, 10: 2.228, 15: 2.131, 30: 2.042}
print("| scene | spp | run 1 Rust/GLSL (95% CI) | run 2 Rust/GLSL | run 2 in run 1's | null, run 1 | null, run 2 |")
print("|---|---|---|---|---|---|---|")
inside = within = total = above = nulls = nulls_in = agree = 0
misses = []
squares = []
alone = []
for key in sorted(one, key=lambda k: (k[0].lower(), k[1])):
    a, b = one[key], two.get(key)
    if not b:
        alone.append(key)
        continue
    total += 1
    r2 = b["ratio"][0]
    ok = a["ratio"][1] <= r2 <= a["ratio"][2]
    inside += ok
    # The two runs' difference against its own interval: a second run as precise as the first
    # lands inside the first's 95% interval only about 83% of the time even when both are right.
    (se1, n1), (se2, n2) = a["se"], b["se"]
    d = math.log(r2 / a["ratio"][0])
    squares.append(d * d)
    agree += abs(d) <= T975.get(n1 + n2 - 2, 2.0) * math.hypot(se1, se2)
    for run in (a, b):
        ratio, low, high = run["ratio"]
        within += high / ratio - 1 <= 0.01 and 1 - low / ratio <= 0.01
        above += low > 1.0
        nulls += 1
        nulls_in += run["null"][1] <= 1.0 <= run["null"][2]
        if not run["null"][1] <= 1.0 <= run["null"][2]:
            misses.append(f"{key[0]} {key[1]} spp run {1 + (run is b)}: " + "%.4f (%.4f to %.4f)" % run["null"])
    row = [key[0], str(key[1]), fmt(a["ratio"]), fmt(b["ratio"]), "yes" if ok else "no", fmt(a["null"]), fmt(b["null"])]
    print("| " + " | ".join(row) + " |")
print()
print(f"{inside} of {total} cells: run 2's ratio inside run 1's interval")
print(f"{agree} of {total} cells: the runs' difference inside its 95% interval; "
      f"rms difference {100 * math.sqrt(sum(squares) / len(squares)):.3f}%")
print(f"{within} of {2 * total} intervals within ±1%; {above} wholly above 1.00")
print(f"{nulls_in} of {nulls} null intervals contain 1")
for miss in misses:
    print(f"  null without 1: {miss}")
if alone:
    print()
    print("Run 1 only (no run 2):")
    print("| scene | spp | run 1 Rust/GLSL (95% CI) | null, run 1 |")
    print("|---|---|---|---|")
    for key in alone:
        print(f"| {key[0]} | {key[1]} | {fmt(one[key]['ratio'])} | {fmt(one[key]['null'])} |")
    cells = [one[key] for key in alone]
    print(f"{sum(c['ratio'][2] / c['ratio'][0] - 1 <= 0.01 and 1 - c['ratio'][1] / c['ratio'][0] <= 0.01 for c in cells)}"
          f" of {len(cells)} intervals within ±1%; {sum(c['ratio'][1] > 1.0 for c in cells)} wholly above 1.00; "
          f"{sum(c['null'][1] <= 1.0 <= c['null'][2] for c in cells)} of {len(cells)} null intervals contain 1")
    for key in alone:
        if not one[key]["null"][1] <= 1.0 <= one[key]["null"][2]:
            print(f"  null without 1: {key[0]} {key[1]} spp run 1: " + "%.4f (%.4f to %.4f)" % one[key]["null"])
