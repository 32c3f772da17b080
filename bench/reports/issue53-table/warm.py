"""Child by child, each warm-up against 1000 ms at the same first placement (raw/w1: first call,
1000 ms, 100 ms, 1000 ms again; raw/w: a later machine, the bench's rule), and the idle gaps
the rule saw.
    python3 warm.py"""
import glob
import json
import os
import re

here = os.path.dirname(os.path.abspath(__file__))
runs = {"100": "w1/w/warm100", "1000 again": "w1/w/warm1000b", "rule": "w/warmrule"}
for scene in ["sphere", "2CylinderEngine.glb"]:
    base = json.load(open(os.path.join(here, "raw", f"w1/w/warm1000-{scene}", "results.json")))["rows"]
    for name, prefix in runs.items():
        rows = json.load(open(os.path.join(here, "raw", f"{prefix}-{scene}", "results.json")))["rows"]
        for row, ref in zip(rows, base):
            q = [a / b for a, b in zip(row["placements"]["median_ms"], ref["placements"]["median_ms"])]
            print(f"{scene:20} {row['spp']:2} spp {row['set']:5} {name:11} against 1000 ms: {min(q):.4f} to {max(q):.4f}")
    log = open(os.path.join(here, "raw", f"w/warmrule-{scene}.log")).read()
    gaps = sorted(float(g) for g in re.findall(r"idle for ([0-9.]+) ms", log))
    short = [g for g in gaps if g <= 500]
    print(f"{scene}: {len(short)} devices found the GPU idle {min(short):.0f} to {max(short):.0f} ms; {len(gaps) - len(short)} after longer")
    for name, prefix in [("1000 ms", "w1/w/warm1000"), ("rule", "w/warmrule")]:
        text = open(os.path.join(here, "raw", f"{prefix}-{scene}.log")).read()
        each = [float(t) for t in re.findall(r"timed by ([0-9]+) ms", text)]
        print(f"  {name}: {len(each)} devices, {sum(each) / len(each):.0f} ms each")
