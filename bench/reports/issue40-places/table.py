#!/usr/bin/env python3
"""Tables of bench/reports/issue40-places/README.md, from raw/. Run: python3 table.py"""
import glob, json, math, os, statistics

HERE = os.path.dirname(os.path.abspath(__file__))
T975 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365}


def interval(logs):
    n = len(logs)
    mean = sum(logs) / n
    sd = statistics.stdev(logs) if n > 1 else 0.0
    half = T975[n - 1] * sd / math.sqrt(n) if n > 1 else 0.0
    return math.exp(mean), math.exp(mean - half), math.exp(mean + half)


def show(est):
    return "%.3f (%.3f to %.3f)" % est


def slow_rounds(rows):
    """Rounds in which some set ran over 1.10x its median round: a slow process."""
    out = set()
    for ms in rows.values():
        med = statistics.median(ms)
        out |= {r for r, m in enumerate(ms) if m > 1.10 * med}
    return out


def cells(pattern):
    for path in sorted(glob.glob(os.path.join(HERE, pattern))):
        d = json.load(open(path))
        by_spp = {}
        for row in d["rows"]:
            by_spp.setdefault(row["spp"], {})[row["set"]] = row["placements"]
        for spp, sets in sorted(by_spp.items()):
            yield path.split("/")[-2], spp, {k: v["median_ms"] for k, v in sets.items()}, sets


def ratio(rows, b, a, keep):
    return interval([math.log(rows[b][r] / rows[a][r]) for r in keep])


def main_table():
    print("| scene | spp | rounds | Rust/GLSL (95% CI) | slow rounds | without them | null |")
    print("|---|---|---|---|---|---|---|")
    for scene, spp, rows, sets in cells("raw/p*/*/results.json"):
        n = len(rows["glsl"])
        every = range(n)
        slow = slow_rounds(rows)
        rest = [r for r in every if r not in slow]
        null = show(ratio(rows, "glsl (copy 1)", "glsl", every)) if "glsl (copy 1)" in rows else "-"
        retimed = sum(len(s.get("retimed", [])) for s in sets.values())
        note = ", ".join(str(r) for r in sorted(slow)) or "-"
        if retimed:
            note += " (%d retimed)" % retimed
        print("| %s | %d | %d | %s | %s | %s | %s |" % (scene, spp, n, show(ratio(rows, "rust", "glsl", every)), note,
              show(ratio(rows, "rust", "glsl", rest)) if slow else "", null))


def warm_table():
    print("\n| TWINRAY_MIN_WARM_MS | processes | placements over 1.10x the fastest | times (ms) |")
    print("|---|---|---|---|")
    for warm in (200, 1000):
        ms = []
        for path in sorted(glob.glob(os.path.join(HERE, "raw/x/w%d-*/results.json" % warm))):
            ms.append(json.load(open(path))["rows"][0]["placements"]["median_ms"])
        flat = [m for p in ms for m in p]
        fast = min(flat)
        slow = sum(m > 1.10 * fast for m in flat)
        print("| %d | %d | %d of %d | %s |" % (warm, len(ms), slow, len(flat), ", ".join("%.2f" % m for m in flat)))


def warm_bench():
    print("\n| scene | spp | warm-up | rounds | Rust/GLSL (95% CI) | slow rounds | null |")
    print("|---|---|---|---|---|---|---|")
    for pattern, warm in (("raw/p*/*/results.json", 200), ("raw/w*/*/results.json", 1000)):
        for scene, spp, rows, sets in cells(pattern):
            if spp != 1 or scene not in ("showcase", "instances"):
                continue
            n = len(rows["glsl"])
            null = show(ratio(rows, "glsl (copy 1)", "glsl", range(n))) if "glsl (copy 1)" in rows else "-"
            slow = ", ".join(str(r) for r in sorted(slow_rounds(rows))) or "-"
            print("| %s | %d | %d ms | %d | %s | %s | %s |" % (scene, spp, warm, n,
                  show(ratio(rows, "rust", "glsl", range(n))), slow, null))


main_table()
warm_table()
warm_bench()
