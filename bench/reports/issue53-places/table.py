#!/usr/bin/env python3
"""Prints every table of this report from raw/ (python3 table.py, from this folder)."""
import json
import math
import os
import statistics as st

HERE = os.path.dirname(os.path.abspath(__file__))


def load(path):
    with open(os.path.join(HERE, "raw", path)) as f:
        return json.load(f)


def places_table(path, label):
    d = load(path)
    print(f"\n{label}: {d['scene']} {d['width']}x{d['height']} at {d['spp']} spp, `{path}`")
    print("| move | set | places | mean ms | sd over places | min..max ms | make ms (median) | over the first set |")
    print("|---|---|---|---|---|---|---|---|")
    for s in d["spreads"]:
        to = s.get("to_first")
        against = f"{to['ratio']:.4f} ({to['low']:.4f} to {to['high']:.4f})" if to else ""
        print(f"| {s['move']} | {s['set']} | {s['places']} | {s['mean_ms']:.4f} | {100 * s['sd']:.2f}% "
              f"| {s['min_ms']:.3f}..{s['max_ms']:.3f} | {s['make_ms']:.1f} | {against} |")


def ratio_cells(path):
    d = load(path)
    out = {}
    for r in d["ratios"]:
        i = r["interval"]
        out[(d["rows"][0]["scene"] if False else r["scene"], r["spp"], r["a"], r["b"])] = (i["ratio"], i["low"], i["high"], i["placements"])
    return out


def glsl_over_rust(cells, scene, spp):
    """GLSL over Rust and the null's ratio, whichever order the bench listed them in."""
    got, null = None, None
    for (sc, sp, a, b), v in cells.items():
        if (sc, sp) != (scene, spp):
            continue
        if (a, b) == ("glsl", "rust"):
            got = v
        elif (a, b) == ("rust", "glsl"):
            got = (1 / v[0], 1 / v[2], 1 / v[1], v[3])
        elif b.endswith("(copy 1)") and b.startswith(a):
            null = v
    return got, null


def fmt(v):
    return f"{v[0]:.3f} ({v[1]:.3f} to {v[2]:.3f}), n={v[3]}" if v else "-"


def runs_table():
    runs = [
        ("r3/a-{s}/results.json", "glsl,rust; places from round 0"),
        ("r4/same-{s}/results.json", "the same command on another machine"),
        ("r4/order-{s}/results.json", "rust,glsl; places from round 0"),
        ("r3/b-{s}/results.json", "rust,glsl; --first-placement 1000"),
        ("r4/places-{s}/results.json", "glsl,rust; --first-placement 2000"),
        ("r4/proc-{s}/results.json", "--processes 8 --placements 6"),
        ("r1/bench-proc/results.json", "--processes 6 --placements 2 (r1's code)"),
    ]
    print("\nGLSL over Rust at 16 spp, 1920x1080, and the null control (the first set over its copy):")
    print("| scene | run | GLSL/Rust (95% CI) | null (95% CI) |")
    print("|---|---|---|---|")
    for scene in ["sphere", "swarm"]:
        for path, what in runs:
            path = path.format(s=scene)
            if not os.path.exists(os.path.join(HERE, "raw", path)):
                continue
            got, null = glsl_over_rust(ratio_cells(path), scene, 16)
            if got:
                print(f"| {scene} | {what} (`{path}`) | {fmt(got)} | {fmt(null)} |")


def table_a():
    print("\nThe first table run (r3, `device-3.sh 420 60 ...`): GLSL over Rust and the null, 60 rounds:")
    print("| scene | spp | GLSL/Rust (95% CI) | width | null (95% CI) |")
    print("|---|---|---|---|---|")
    for scene in ["sphere", "swarm", "cone", "box", "meshes", "showcase"]:
        cells = ratio_cells(f"r3/a-{scene}/results.json")
        for spp in [1, 16]:
            got, null = glsl_over_rust(cells, scene, spp)
            width = (got[2] - got[1]) / 2 / got[0]
            print(f"| {scene} | {spp} | {got[0]:.3f} ({got[1]:.3f} to {got[2]:.3f}) | ±{100 * width:.1f}% | {null[0]:.3f} ({null[1]:.3f} to {null[2]:.3f}) |")


def halves():
    print("\nEach run's mean in its first and second half of rounds (sphere, 16 spp): a run is consistent")
    print("with itself, and runs that start at other places disagree.")
    print("| run | set | mean ms | first half | second half |")
    print("|---|---|---|---|---|")
    for path in ["r3/a-sphere/results.json", "r4/places-sphere/results.json", "r3/b-sphere/results.json"]:
        for row in load(path)["rows"]:
            if row["spp"] != 16 or "copy" in row["set"]:
                continue
            ms = row["placements"]["median_ms"]
            n = len(ms)
            print(f"| `{path}` | {row['set']} | {st.mean(ms):.4f} | {st.mean(ms[:n // 2]):.4f} | {st.mean(ms[n // 2:]):.4f} |")


if __name__ == "__main__":
    places_table("r1/places-sphere16.json", "r1, salted spacers")
    places_table("r1/places-swarm16.json", "r1, salted spacers")
    places_table("r2/places-sphere16-libraries.json", "r2, linked from libraries")
    places_table("r2/places-sphere16-monolithic.json", "r2, monolithic")
    places_table("r2/places-swarm16-monolithic.json", "r2, monolithic")
    table_a()
    runs_table()
    halves()
