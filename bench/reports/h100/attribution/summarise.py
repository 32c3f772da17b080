#!/usr/bin/env python3
"""The table of README.md from spp-1/ratios.csv and spp-16/ratios.csv: per scene and samples
per pixel, Rust / GLSL, GLSL with the Rust ray generation / GLSL, Rust / that mix (what the
Rust stages other than ray generation cost), and Rust with bottom-tested loops / Rust; each
with its 95% interval over placements, in bold where the interval excludes 1."""
import csv
import pathlib

HERE = pathlib.Path(__file__).parent


def label(s):
    if s in ("rust", "glsl"):
        return s
    if "r_dowhile" in s:
        return "dowhile"
    if s.startswith("rust,miss=glsl"):  # glsl,raygen=rust as the bench prints it
        return "mix"
    raise ValueError(s)


ratios = {}
for spp in (1, 16):
    for r in csv.DictReader(open(HERE / f"spp-{spp}" / "ratios.csv")):
        key = (r["scene"], spp, label(r["a"]), label(r["b"]))
        ratios[key] = tuple(float(r[k]) for k in ("ratio", "ci_low", "ci_high"))


def get(scene, spp, a, b):
    if (scene, spp, a, b) in ratios:
        return ratios[(scene, spp, a, b)]
    r, lo, hi = ratios[(scene, spp, b, a)]
    return 1 / r, 1 / hi, 1 / lo


def cell(x):
    text = f"{x[0]:.3f} ({x[1]:.3f} to {x[2]:.3f})"
    return f"**{text}**" if x[1] > 1 or x[2] < 1 else text


print("| scene | spp | Rust / GLSL | GLSL + Rust raygen / GLSL | Rust / (GLSL + Rust raygen) | dowhile / Rust |")
print("|---|---:|---:|---:|---:|---:|")
for scene in sorted({k[0] for k in ratios}):
    for spp in (1, 16):
        pairs = [("rust", "glsl"), ("mix", "glsl"), ("rust", "mix"), ("dowhile", "rust")]
        print(f"| {scene} | {spp} | " + " | ".join(cell(get(scene, spp, a, b)) for a, b in pairs) + " |")
