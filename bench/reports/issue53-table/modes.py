"""Per cell and set: how a device's time depends on the spacers made before the set (0 to 7,
drawn per place by placement::spacer_sets). A set made first on a fresh device (0 spacers)
against the same set after at least one, and the spread of the latter.
    python3 modes.py"""
import glob
import json
import math
import os

here = os.path.dirname(os.path.abspath(__file__))
M = (1 << 64) - 1
SEED = 0x7417_2A79_5EED_0026  # placement::SEED


def spacers(place):
    """placement::spacer_sets(place, 1).len() as the commit of this report drew it."""
    state = (SEED ^ (place * 0x9E3779B97F4A7C15 & M)) & M
    state = (state + 0x9E3779B97F4A7C15) & M
    z = state
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & M
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & M
    return (z ^ (z >> 31)) % 8


def geo(values):
    return math.exp(sum(math.log(v) for v in values) / len(values))


first_vs_after, spreads = [], []
for path in sorted(glob.glob(os.path.join(here, "raw", "t[12]*", "*", "results.json"))):
    for row in json.load(open(path))["rows"]:
        p = row["placements"]
        pairs = [(spacers(f), t) for f, t in zip(p["first_placement"], p["median_ms"])]
        after = [t for c, t in pairs if c >= 1]
        first = [t for c, t in pairs if c == 0]
        spreads.append(max(after) / min(after) - 1)
        if first:
            first_vs_after.append((geo(first) / geo(after), row["set"], row["spp"], path.split(os.sep)[-2]))
spreads.sort()
print(f"{len(spreads)} set cells; after at least one spacer, max/min over devices: median {spreads[len(spreads) // 2] * 100:.2f}%, "
      f"90th percentile {spreads[int(len(spreads) * 0.9)] * 100:.2f}%, widest {spreads[-1] * 100:.2f}%")
first_vs_after.sort()
far = [f for f in first_vs_after if abs(f[0] - 1) > 0.005]
print(f"made first (0 spacers) against after: {len(far)} of {len(first_vs_after)} set cells more than 0.5% away, "
      f"from {first_vs_after[0][0]:.3f} ({first_vs_after[0][3]} {first_vs_after[0][1]} {first_vs_after[0][2]} spp) "
      f"to {first_vs_after[-1][0]:.3f} ({first_vs_after[-1][3]} {first_vs_after[-1][1]} {first_vs_after[-1][2]} spp)")


# The table again over the devices with spacers only: Rust against GLSL per cell, unpaired
# (a round's partner may have had none), a Welch interval on the logs; does run 2 land in run 1's?
def t_975(df):
    table = [(1, 12.706), (2, 4.303), (3, 3.182), (4, 2.776), (5, 2.571), (6, 2.447), (8, 2.306), (10, 2.228),
             (12, 2.179), (14, 2.145), (16, 2.120), (18, 2.101), (20, 2.086), (25, 2.060), (30, 2.042)]
    return next((t for d, t in table if d >= df), 2.0)


def spaced_cells(prefix):
    cells = {}
    for path in glob.glob(os.path.join(here, "raw", prefix + "*", "*", "results.json")):
        rows = json.load(open(path))["rows"]
        logs = {}
        for row in rows:
            p = row["placements"]
            kept = [math.log(t) for f, t in zip(p["first_placement"], p["median_ms"]) if spacers(f) >= 1]
            logs[(row["spp"], row["set"])] = kept
        for spp in {spp for spp, _ in logs}:
            a, b = logs[(spp, "rust")], logs[(spp, "glsl")]
            mean = lambda v: sum(v) / len(v)
            var = lambda v: sum((x - mean(v)) ** 2 for x in v) / (len(v) - 1)
            d = mean(a) - mean(b)
            va, vb = var(a) / len(a), var(b) / len(b)
            df = (va + vb) ** 2 / (va**2 / (len(a) - 1) + vb**2 / (len(b) - 1))
            half = t_975(df) * math.sqrt(va + vb)
            cells[(rows[0]["scene"], spp)] = (math.exp(d), math.exp(d - half), math.exp(d + half))
    return cells


one, two = spaced_cells("t1"), spaced_cells("t2")
halves = sorted(max(h / r - 1, 1 - l / r) for run in (one, two) for r, l, h in run.values())
inside = [k for k in one if k in two and one[k][1] <= two[k][0] <= one[k][2]]
rms = math.sqrt(sum(math.log(two[k][0] / one[k][0]) ** 2 for k in one) / len(one))
print(f"over devices with spacers: intervals ±{halves[len(halves) // 2] * 100:.2f}% (median), widest ±{halves[-1] * 100:.2f}%; "
      f"run 2 inside run 1's in {len(inside)} of {len(one)} cells, {rms * 100:.3f}% apart (rms)")
for k in sorted(one):
    r, l, h = one[k]
    if l > 1.0:
        print(f"  Rust slower, both runs' intervals above 1: {k[0]} {k[1]} spp {r:.4f} ({l:.4f} to {h:.4f}), run 2 {two[k][0]:.4f}"
              if two[k][1] > 1.0 else f"  run 1 only above 1: {k[0]} {k[1]} spp {r:.4f}, run 2 {two[k][0]:.4f} ({two[k][1]:.4f} to {two[k][2]:.4f})")

# Run 3 (`device-table.sh t3 glsl,rust 2000 150 16 lights torus`), built with every place
# after 1 to 7 spacers: its paired intervals against runs 1 and 2 over their spaced devices.
for path in sorted(glob.glob(os.path.join(here, "raw", "t3", "*", "results.json"))):
    for q in json.load(open(path))["ratios"]:
        iv, key = q["interval"], (q["scene"], q["spp"])
        if (q["a"], q["b"]) == ("glsl", "rust"):
            r3 = (1 / iv["ratio"], 1 / iv["high"], 1 / iv["low"])
            print(f"run 3 {key[0]} {key[1]} spp: Rust/GLSL {r3[0]:.4f} ({r3[1]:.4f} to {r3[2]:.4f}); "
                  f"runs 1 and 2 over spaced devices {one[key][0]:.4f} and {two[key][0]:.4f}")
        elif q["null_control"]:
            print(f"run 3 {key[0]} {key[1]} spp: null {iv['ratio']:.4f} ({iv['low']:.4f} to {iv['high']:.4f})")
