"""Prints each compare JSON of a run folder as: A/B medians, the ratio with its interval, and
every placement's median of each set with its position in the placement's order (@0: built
first). python3 summarise.py FOLDER"""
import glob, json, statistics, sys

for f in sorted(glob.glob(sys.argv[1] + "/*.json")):
    try:
        n = json.load(open(f))
    except ValueError:
        continue
    if "placements_a" in n:
        t = n["timing"]
        print(f"{f.split('/')[-1]}: {n['gpu_ms_a']:.3f} / {n['gpu_ms_b']:.3f} ms, a/b {t['ratio']:.3f} ({t['low']:.3f} to {t['high']:.3f})")
        for k in "ab":
            p = n["placements_" + k]
            print(f"    {k}: " + " ".join(f"{m:.3f}@{q}" for m, q in zip(p["median_ms"], p["position"])))
    elif "rows" in n and "ratios" in n:
        print(f.split("/")[-1])
        for r in n["rows"]:
            p = r["placements"]
            print(f"    {r['scene']} {r['spp']} spp {r['set']}: median {statistics.median(p['median_ms']):.3f}: " + " ".join(f"{m:.3f}@{q}" for m, q in zip(p["median_ms"], p["position"])))
        for r in n["ratios"]:
            i = r["interval"]
            print(f"    {r['scene']} {r['spp']} spp {r['a']} / {r['b']}: {i['ratio']:.4f} ({i['low']:.4f} to {i['high']:.4f})")
    elif "ratio" in n and n.get("gpu_ms_a"):
        print(f"{f.split('/')[-1]}: {n['gpu_ms_a']:.3f} / {n['gpu_ms_b']:.3f} ms, a/b {n['ratio']:.3f} (old instrument)")
