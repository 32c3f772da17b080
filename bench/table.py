"""The tables of bench/reports/, from what twinray wrote: one script for every report.

    python3 bench/table.py ratios RUN [RUN2] [--pair A,B]
        The A/B table (default rust,glsl) of `twinray bench` runs. A run is a folder holding
        one folder per scene with its `results.json` (as `bench --out` writes it), or several
        such folders joined by `+` (a later folder's scenes replace an earlier's). A run that
        names B first is read as the inverse. With RUN2: whether RUN2's ratio lies in RUN's
        interval, whether the runs' difference lies in its own interval, and the null controls.

    python3 bench/table.py between RUN RUN2 [RUN RUN2 ...]
        For each pair of runs, how far they differ beyond what their intervals predict: the rms
        of the cells' log differences, the rms their standard errors predict, the between-run
        part left, the mean difference and the rms of the z scores (1 when intervals are right).

    python3 bench/table.py stability FILE [OLD]
        The accuracy table of docs/numerics.md from `twinray stability --json` output (a `.gz`
        is read as is): per case the robust formulas' relative t error p99 in each set, its
        condition multiple, the rays they got wrong, the transform's and the driver's parts,
        with OLD the Rust set's p99 before, and whether the case meets the targets its file in
        probes/stability/ names now. Run from the repository root.
"""
import glob
import gzip
import json
import math
import os
import statistics
import sys
import tomllib

# Two-sided 97.5% points of Student's t, by degrees of freedom.
T975 = {5: 2.571, 10: 2.228, 15: 2.131, 30: 2.042}


def load(folder, pair):
    """One run's cells: (scene, spp) -> ratio (value, low, high), its standard error, null."""
    a, b = pair
    cells = {}
    for path in sorted(glob.glob(os.path.join(folder, "*", "results.json"))):
        for r in json.load(open(path))["ratios"]:
            iv = r["interval"]
            ratio, low, high = iv["ratio"], iv["low"], iv["high"]
            se = (iv["log_sd"] / math.sqrt(iv["placements"]), iv["placements"])
            cell = cells.setdefault((r["scene"], r["spp"]), {})
            if (r["a"], r["b"]) == (b, a):
                cell["ratio"], cell["se"] = (1 / ratio, 1 / high, 1 / low), se
            elif (r["a"], r["b"]) == (a, b):
                cell["ratio"], cell["se"] = (ratio, low, high), se
            elif r["null_control"]:
                cell["null"] = (ratio, low, high)
    return {k: c for k, c in cells.items() if "ratio" in c}


def layered(name, pair):
    cells = {}
    for folder in name.split("+"):
        cells.update(load(folder, pair))
    return cells


def fmt(c):
    if c is None:
        return "-"
    ratio, low, high = c
    half = max(high / ratio - 1, 1 - low / ratio) * 100
    return f"{ratio:.3f} ({low:.3f} to {high:.3f}) ±{half:.1f}%"


def within_1pc(c):
    return c[2] / c[0] - 1 <= 0.01 and 1 - c[1] / c[0] <= 0.01


def contains_1(c):
    return c is not None and c[1] <= 1.0 <= c[2]


def ratios(args):
    pair = ("rust", "glsl")
    if "--pair" in args:
        i = args.index("--pair")
        pair = tuple(args[i + 1].split(","))
        args = args[:i] + args[i + 2:]
    one = layered(args[0], pair)
    two = layered(args[1], pair) if len(args) > 1 else None
    name = f"{pair[0]}/{pair[1]}"
    if two is None:
        print(f"| scene | spp | {name} (95% CI) | null control |")
        print("|---|---|---|---|")
        for key in sorted(one, key=lambda k: (k[0].lower(), k[1])):
            print(f"| {key[0]} | {key[1]} | {fmt(one[key]['ratio'])} | {fmt(one[key].get('null'))} |")
        cells = list(one.values())
        values = [c["ratio"][0] for c in cells]
        print(f"\n{len(cells)} cells; median {name} {statistics.median(values):.3f}; "
              f"{sum(within_1pc(c['ratio']) for c in cells)} intervals within ±1%, "
              f"{sum(c['ratio'][1] > 1.0 for c in cells)} wholly above 1.00; "
              f"{sum(contains_1(c.get('null')) for c in cells)} of {len(cells)} null intervals contain 1")
        return
    print(f"| scene | spp | run 1 {name} (95% CI) | run 2 {name} | run 2 in run 1's | null, run 1 | null, run 2 |")
    print("|---|---|---|---|---|---|---|")
    inside = agree = within = above = nulls_in = 0
    squares, alone, misses = [], [], []
    for key in sorted(one, key=lambda k: (k[0].lower(), k[1])):
        a, b = one[key], two.get(key)
        if not b:
            alone.append(key)
            continue
        r2 = b["ratio"][0]
        ok = a["ratio"][1] <= r2 <= a["ratio"][2]
        inside += ok
        # A second run as precise as the first lands inside the first's 95% interval only about
        # 83% of the time even when both are right: the difference has an interval of its own.
        (se1, n1), (se2, n2) = a["se"], b["se"]
        d = math.log(r2 / a["ratio"][0])
        squares.append(d * d)
        agree += abs(d) <= T975.get(n1 + n2 - 2, 2.0) * math.hypot(se1, se2)
        for run in (a, b):
            within += within_1pc(run["ratio"])
            above += run["ratio"][1] > 1.0
            nulls_in += contains_1(run.get("null"))
            if not contains_1(run.get("null")):
                misses.append(f"{key[0]} {key[1]} spp run {1 + (run is b)}: {fmt(run.get('null'))}")
        row = [key[0], str(key[1]), fmt(a["ratio"]), fmt(b["ratio"]), "yes" if ok else "no",
               fmt(a.get("null")), fmt(b.get("null"))]
        print("| " + " | ".join(row) + " |")
    total = len(squares)
    print(f"\n{inside} of {total} cells: run 2's ratio inside run 1's interval")
    if total:
        print(f"{agree} of {total} cells: the runs' difference inside its 95% interval; "
              f"rms difference {100 * math.sqrt(sum(squares) / total):.3f}%")
    print(f"{within} of {2 * total} intervals within ±1%; {above} wholly above 1.00")
    print(f"{nulls_in} of {2 * total} null intervals contain 1")
    for miss in misses:
        print(f"  null without 1: {miss}")
    if alone:
        print("\nRun 1 only: " + ", ".join(f"{k[0]} {k[1]} spp {fmt(one[k]['ratio'])}" for k in alone))


def between(args):
    print("| runs | cells | rms difference | predicted | between runs | mean difference | rms z |")
    print("|---|---|---|---|---|---|---|")
    pair = ("rust", "glsl")
    for a, b in zip(args[::2], args[1::2]):
        one, two = layered(a, pair), layered(b, pair)
        ds, variances, zs = [], [], []
        for key in one:
            if key not in two:
                continue
            (se1, _), (se2, _) = one[key]["se"], two[key]["se"]
            d = math.log(two[key]["ratio"][0] / one[key]["ratio"][0])
            ds.append(d)
            variances.append(se1 * se1 + se2 * se2)
            zs.append(d / math.hypot(se1, se2))
        observed = math.sqrt(sum(d * d for d in ds) / len(ds))
        predicted = math.sqrt(sum(variances) / len(variances))
        left = math.sqrt(max(observed * observed - predicted * predicted, 0.0))
        rms_z = math.sqrt(sum(z * z for z in zs) / len(zs))
        print(f"| {os.path.basename(a)} / {os.path.basename(b)} | {len(ds)} | {observed * 100:.3f}% | "
              f"{predicted * 100:.3f}% | {left * 100:.3f}% | {statistics.mean(ds) * 100:+.3f}% | {rms_z:.2f} |")


def read_json(path):
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rt") as f:
        return json.load(f)


def stability(args):
    rows = read_json(args[0])
    old = read_json(args[1]) if len(args) > 1 else []

    def find(rows, case, set_):
        return next((r for r in rows if (r["case"], r["formula"]) == (case, "robust") and r["set"].endswith(set_)),
                    None)

    def wrong(r):
        return r["false_hits"] + r["false_misses"] + r["wrong_object"] + r["through"]

    def meets(case, r):
        # As `twinray stability` judges it, by the case's targets as they are now: none wrong,
        # the p99s within the case's bounds, the condition multiple within 8 where none is named.
        with open(f"probes/stability/{case}.toml", "rb") as f:
            targets = tomllib.load(f).get("targets", {})
        relative = targets.get("max_relative_t_p99", float("inf"))
        multiple = targets.get("max_condition_multiple_p99", 8.0)
        return (r["false_hits"] + r["false_misses"] + r["wrong_object"] == 0 and r["decided"] > 0
                and r["relative_t_error"]["p99"] <= relative and r["condition_multiple"]["p99"] <= multiple)

    def part(r, name):
        d = (r.get("t_error_by_source") or {}).get(name)
        return f"{d['p99']:.1e}" if d else "n/a"

    print(f"Device: {rows[0]['device']}.\n")
    before = " rust p99 before |" if old else ""
    print("| case | rust t p99 | glsl t p99 | condition multiple p99 (rust, glsl) | wrong (rust, glsl) | "
          f"transform p99 | driver's p99 |{before} target |")
    print("|---|---|---|---|---|---|---|" + ("---|" if old else "") + "---|")
    cases = sorted({r["case"] for r in rows})
    met, worst, shown = 0, 0.0, 0
    for case in cases:
        rust, glsl = find(rows, case, "rust"), find(rows, case, "glsl")
        if rust is None or glsl is None:
            continue
        shown += 1
        ok = meets(case, rust) and meets(case, glsl)
        met += ok
        cm = (rust["condition_multiple"]["p99"], glsl["condition_multiple"]["p99"])
        worst = max(worst, *cm)
        was = find(old, case, "rust") if old else None
        was = (f" {was['relative_t_error']['p99']:.1e} |" if was else " - |") if old else ""
        print(f"| {case} | {rust['relative_t_error']['p99']:.1e} | {glsl['relative_t_error']['p99']:.1e} | "
              f"{cm[0]:.2f}, {cm[1]:.2f} | {wrong(rust)}, {wrong(glsl)} of {rust['decided']} | "
              f"{part(rust, 'transform')} | {part(rust, 'driver')} |{was} {'met' if ok else 'MISSED'} |")
    print(f"\n{met} of {shown} cases meet their targets in both sets; "
          f"the largest condition multiple p99 is {worst:.2f}.")


if __name__ == "__main__":
    modes = {"ratios": ratios, "between": between, "stability": stability}
    if len(sys.argv) < 3 or sys.argv[1] not in modes:
        sys.exit(__doc__)
    modes[sys.argv[1]](sys.argv[2:])
