#!/usr/bin/env python3
"""Each set's median GPU time per scene from device-sets.sh archives, and its ratio to the
first set (glsl): below 1, faster than GLSL. Sets with one stage swapped print as
written (bench prints them canonically).
    python3 sets.py raw/r16.tgz [raw/r1.tgz ...]"""
import json
import sys
import tarfile

SHORT = [
    # How bench prints `rust,raygen=glsl` and `glsl,raygen=rust`.
    ("glsl,miss=rust,intersection=rust,closest_hit=rust,any_hit=rust,callable=rust,compute=rust", "rust,raygen=glsl"),
    ("rust,miss=glsl,intersection=glsl,closest_hit=glsl,any_hit=glsl,callable=glsl,compute=glsl", "glsl,raygen=rust"),
    ("procedural_closest_hit=", "ch="),
]

for archive in sys.argv[1:]:
    with tarfile.open(archive) as tar:
        for member in sorted(tar.getmembers(), key=lambda m: m.name):
            if not member.name.endswith("results.json"):
                continue
            base = None
            for row in json.load(tar.extractfile(member))["rows"]:
                label = row["set"]
                for long, short in SHORT:
                    label = label.replace(long, short)
                ms = row["gpu_ms"]["median"]
                base = base or ms
                print("%-9s %2d spp  %-34s %8.4f ms  %.4f" % (row["scene"], row["spp"], label, ms, ms / base))
