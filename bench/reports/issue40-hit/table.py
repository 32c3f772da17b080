#!/usr/bin/env python3
"""Tables of bench/reports/issue40-hit/README.md, from raw/. Run: python3 table.py

Each bench reports A / B (time of A over time of B) with its 95% interval; here every
ratio is turned to B-language over A where one side is plain `glsl`, so that a ratio above
1 means the other set is slower than GLSL.
"""
import csv, glob, json, os, statistics

HERE = os.path.dirname(os.path.abspath(__file__))


def rows(run, root=os.path.join(HERE, "raw")):
    for path in sorted(glob.glob(os.path.join(root, run, "*", "ratios.csv"))):
        scene = path.split("/")[-2]
        stacks = {}
        results = os.path.join(os.path.dirname(path), "results.json")
        if os.path.exists(results):
            for r in json.load(open(results))["rows"]:
                stacks[(r["set"], r["spp"])] = r["raygen_stack_bytes"]
        for r in csv.DictReader(open(path)):
            yield scene, r, stacks


def against_glsl(r):
    """(other set, other/GLSL, low, high) for a row with `glsl` on one side, else None."""
    ratio, low, high = float(r["ratio"]), float(r["ci_low"]), float(r["ci_high"])
    if r["a"] == "glsl":
        return r["b"], 1 / ratio, 1 / high, 1 / low
    if r["b"] == "glsl":
        return r["a"], ratio, low, high
    return None


def short(name):
    name = name.replace("/tmp/twinray-bench/v40/B", "B (no checks)")
    if name.startswith("rust,miss=glsl"):
        return "Rust raygen only"
    return name


def table(run, title):
    print("\n## %s (raw/%s)\n" % (title, run))
    print("| scene | spp | set | set/GLSL (95% CI) | places | raygen stack bytes (GLSL, set) |")
    print("|---|---|---|---|---|---|")
    cells = []
    for scene, r, stacks in rows(run):
        got = against_glsl(r)
        if got is None:
            continue
        other, ratio, low, high = got
        spp = int(r["spp"])
        stack = "%s, %s" % (stacks.get(("glsl", spp), "-"), stacks.get((other, spp), "-"))
        print("| %s | %d | %s | %.3f (%.3f to %.3f) | %s | %s |" % (scene, spp, short(other), ratio, low, high,
                                                                 r["placements"], stack))
        if other == "rust":
            cells.append((scene, spp, ratio, low))
    return cells


def summary(cells):
    ratios = [c[2] for c in cells]
    print("\nRust/GLSL over %d cells: median %.3f; intervals wholly above 1.01: %s; wholly above 1.00: %s" % (
        len(cells), statistics.median(ratios),
        ", ".join("%s-%d" % c[:2] for c in cells if c[3] > 1.01) or "none",
        ", ".join("%s-%d" % c[:2] for c in cells if c[3] > 1.00) or "none"))


table("a1", "Attribution before the change: one stage at a time from Rust, 1 spp")
table("h1", "The change (B) against GLSL and the committed Rust, 1 spp")
table_cells = []
for run in ("t1", "t2", "t3"):
    table_cells += table(run, "The table with the change landed, 1 and 16 spp")
summary(table_cells)
summary(table("r1", "Second run of the three cells that were wholly above 1.01, 5 places"))


def estimates(runs, name, root=os.path.join(HERE, "raw")):
    """{(scene, spp): [(run, ratio, low, high)]} of set `name` over GLSL in `runs`."""
    out = {}
    for run in runs:
        for scene, r, _ in rows(run, root):
            got = against_glsl(r)
            if got and got[0] == name:
                out.setdefault((scene, int(r["spp"])), []).append((run,) + got[1:])
    return out


def repeats(title, groups):
    """Whether each run's estimate of a cell lies inside each other run's interval."""
    print("\n## %s\n" % title)
    held = pairs = 0
    for cell, runs in sorted(groups.items()):
        if len(runs) < 2:
            continue
        print("- %s-%d: %s" % (cell[0], cell[1], "; ".join("%s %.3f (%.3f to %.3f)" % r for r in runs)))
        for a in runs:
            for b in runs:
                if a is not b:
                    pairs += 1
                    held += b[2] <= a[1] <= b[3]
    print("\nAn estimate inside the other run's interval: %d of %d ordered pairs" % (held, pairs))


PLACES = os.path.join(HERE, "..", "issue40-places", "raw")
old = estimates(("a1", "h1"), "rust")
for cell, runs in estimates(("p1", "p2", "p4"), "rust", PLACES).items():
    if cell in old:  # the 1 spp cells of the sessions before, 5 or 6 places, 200 ms warm-up
        old[cell] += [("places-" + r[0],) + r[1:] for r in runs]
repeats("Repeats of the committed Rust set of 0e03f2b", old)
new = estimates(("h1",), "/tmp/twinray-bench/v40/B")
for cell, runs in estimates(("t1", "t2", "t3", "r1"), "rust").items():
    new.setdefault(cell, []).extend(runs)
repeats("Repeats of the procedural closest hit without checks (B in h1, the landed set after)", new)
