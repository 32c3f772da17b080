"""The accuracy table of docs/numerics.md from `twinray stability --json` output: per case, the
robust formulas' relative t error p99 on the totals in each set, the rays they got wrong (false
hits, false misses, wrong object, through the first surface), what the driver's object-space
ray would have given, and the naive formula's figures where the case has one.
    python3 table.py raw/lavapipe.json"""
import json
import sys

rows = json.load(open(sys.argv[1]))
cases = sorted({r["case"] for r in rows})


def find(case, formula, set_):
    return next((r for r in rows if (r["case"], r["formula"], r["set"]) == (case, formula, set_)), None)


def wrong(r):
    return r["false_hits"] + r["false_misses"] + r["wrong_object"] + r["through"]


def driver(r):
    split = r.get("t_error_by_source") or {}
    d = split.get("driver")
    return f"{d['p99']:.1e}" if d else "n/a"


device = rows[0]["device"]
print(f"Device: {device}.\n")
print("| case | rust t p99 | glsl t p99 | wrong (rust, glsl) | driver's p99 | naive t p99 | naive wrong | target |")
print("|---|---|---|---|---|---|---|---|")
met = 0
for case in cases:
    rust, glsl = find(case, "robust", "rust"), find(case, "robust", "glsl")
    naive = find(case, "naive", "rust")
    ok = not rust["failures"] and not glsl["failures"]
    met += ok
    n_t = f"{naive['relative_t_error']['p99']:.1e}" if naive else "-"
    n_w = f"{wrong(naive)} of {naive['decided']}" if naive else "-"
    print(f"| {case} | {rust['relative_t_error']['p99']:.1e} | {glsl['relative_t_error']['p99']:.1e} | "
          f"{wrong(rust)}, {wrong(glsl)} of {rust['decided']} | {driver(rust)} | {n_t} | {n_w} | "
          f"{'met' if ok else 'MISSED'} |")
print(f"\n{met} of {len(cases)} cases meet their targets in both sets.")
