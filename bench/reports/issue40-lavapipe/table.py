"""Prints run.sh's ratios as a Markdown table: per scene and spp, new over old (time of the
set at HEAD over the same language's set from da63c8e) with its 95% interval, and the null
control (old over its salted copy). Usage: python3 table.py OUT/rust/ratios.csv ..."""
import csv
import sys

for path in sys.argv[1:]:
    rows = list(csv.DictReader(open(path)))
    print(f"\n{path}\n\n| scene | spp | new/old (95% CI) | null (95% CI) |\n|---|---:|---:|---:|")
    cells = {}
    for r in rows:
        key = (r["scene"], int(r["spp"]))
        inv = lambda x: 1.0 / float(x)
        if r["null_control"] == "true":
            cells.setdefault(key, {})["null"] = (float(r["ratio"]), float(r["ci_low"]), float(r["ci_high"]))
        elif "(copy" not in r["b"]:
            # a is the old set, b the new: new/old is 1/ratio, its interval flipped.
            cells.setdefault(key, {})["new"] = (inv(r["ratio"]), inv(r["ci_high"]), inv(r["ci_low"]))
    for (scene, spp), c in sorted(cells.items()):
        f = lambda t: f"{t[0]:.3f} ({t[1]:.3f} to {t[2]:.3f})" if t else "n/a"
        print(f"| {scene} | {spp} | {f(c.get('new'))} | {f(c.get('null'))} |")
    news = sorted(c["new"][0] for c in cells.values() if "new" in c)
    above = [k for k, c in cells.items() if "new" in c and c["new"][1] > 1.0]
    print(f"\nmedian new/old {news[len(news) // 2]:.3f} over {len(news)} cells; wholly above 1: {sorted(above)}")
