"""The accuracy table of docs/numerics.md from `twinray stability --json` output: per case, the
robust formulas' relative t error p99 on the totals in each set, that error in units of its
condition (p99), the rays they got wrong (false hits, false misses, wrong object, through the
first surface), the stages' transform's part and what the driver's object-space ray would have
given (Rust set), and with a second file (the same suite with the previous commit's sets,
`--sets "target/o-rust;target/o-glsl"`), the Rust set's p99 before.
Whether a case meets its targets is judged again here from its file in probes/stability/ (as
`twinray stability` judges it: none wrong, and the p99s within the case's bounds, the condition
multiple's within 8 where the case names none), so that a run from before a target was
rewritten reads as the suite would judge it now.
    python3 table.py raw/lavapipe.json [raw/lavapipe-old.json]   (from the repository root)"""
import json
import sys
import tomllib

rows = json.load(open(sys.argv[1]))
old = json.load(open(sys.argv[2])) if len(sys.argv) > 2 else []
cases = sorted({r["case"] for r in rows})


def find(rows, case, set_):
    return next((r for r in rows if (r["case"], r["formula"]) == (case, "robust") and r["set"].endswith(set_)), None)


def wrong(r):
    return r["false_hits"] + r["false_misses"] + r["wrong_object"] + r["through"]


def meets(case, r):
    with open(f"probes/stability/{case}.toml", "rb") as f:
        targets = tomllib.load(f).get("targets", {})
    relative = targets.get("max_relative_t_p99", float("inf"))
    multiple = targets.get("max_condition_multiple_p99", 8.0)
    return (r["false_hits"] + r["false_misses"] + r["wrong_object"] == 0 and r["decided"] > 0
            and r["relative_t_error"]["p99"] <= relative and r["condition_multiple"]["p99"] <= multiple)


def part(r, name):
    split = r.get("t_error_by_source") or {}
    d = split.get(name)
    return f"{d['p99']:.1e}" if d else "n/a"


print(f"Device: {rows[0]['device']}.\n")
before = " rust p99 before |" if old else ""
print(f"| case | rust t p99 | glsl t p99 | condition multiple p99 (rust, glsl) | wrong (rust, glsl) | transform p99 | driver's p99 |{before} target |")
print("|---|---|---|---|---|---|---|" + ("---|" if old else "") + "---|")
met, worst = 0, 0.0
for case in cases:
    rust, glsl = find(rows, case, "rust"), find(rows, case, "glsl")
    if rust is None or glsl is None:
        continue
    ok = meets(case, rust) and meets(case, glsl)
    met += ok
    cm = (rust["condition_multiple"]["p99"], glsl["condition_multiple"]["p99"])
    worst = max(worst, *cm)
    was = find(old, case, "rust") if old else None
    was = (f" {was['relative_t_error']['p99']:.1e} |" if was else " - |") if old else ""
    print(f"| {case} | {rust['relative_t_error']['p99']:.1e} | {glsl['relative_t_error']['p99']:.1e} | "
          f"{cm[0]:.2f}, {cm[1]:.2f} | {wrong(rust)}, {wrong(glsl)} of {rust['decided']} | {part(rust, 'transform')} | "
          f"{part(rust, 'driver')} |{was} {'met' if ok else 'MISSED'} |")
print(f"\n{met} of {len(cases)} cases meet their targets in both sets; the largest condition multiple p99 is {worst:.2f}.")
