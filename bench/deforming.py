#!/usr/bin/env python3
"""A sheet of N x N vertices as a glTF model whose mesh deforms over a 2-second clip, for
`twinray animate-bench` and `twinray render --frames`: with `skin`, its upper half bends a
quarter turn about the x axis on a second joint and back (weights blended over a band across
the middle); with `morph`, one morph target raises a bump pattern whose weight goes 0, 1, 0;
`still` is the sheet alone, unanimated (for load time and memory).
Writes NAME.gltf and NAME.bin.

    python3 bench/deforming.py skin 1024 out/skin-1024
"""

import json
from array import array
import math
import struct
import sys


def sheet(n):
    """Positions and normals of an n x n grid over [-1, 1]^2 at z = 0 (flat float arrays, three
    per vertex), and its triangles' indices."""
    positions, normals, indices = array("f"), array("f"), array("I")
    step = 2.0 / (n - 1)
    for j in range(n):
        y = j * step - 1.0
        for i in range(n):
            positions.extend((i * step - 1.0, y, 0.0))
    normals.extend((0.0, 0.0, 1.0) * (n * n))
    for j in range(n - 1):
        row = j * n
        for a in range(row, row + n - 1):
            indices.extend((a, a + 1, a + n + 1, a, a + n + 1, a + n))
    return positions, normals, indices


class Blob:
    """One buffer; each view 4-byte aligned."""

    def __init__(self):
        self.data, self.views, self.accessors = bytearray(), [], []

    def add(self, fmt, values, count, kind, component, **extra):
        """`values`: an array (written as it is) or tuples and numbers packed by `fmt`."""
        while len(self.data) % 4:
            self.data.append(0)
        start = len(self.data)
        if isinstance(values, array):
            self.data += values.tobytes()
        else:
            flat = [x for v in values for x in (v if isinstance(v, tuple) else (v,))]
            self.data += struct.pack("<" + fmt * len(values), *flat)
        self.views.append({"buffer": 0, "byteOffset": start, "byteLength": len(self.data) - start})
        self.accessors.append({"bufferView": len(self.views) - 1, "componentType": component, "count": count, "type": kind, **extra})
        return len(self.accessors) - 1


def main(kind, n, stem):
    positions, normals, indices = sheet(n)
    vertices = n * n
    blob = Blob()
    attributes = {
        "POSITION": blob.add("3f", positions, vertices, "VEC3", 5126, min=[-1, -1, 0], max=[1, 1, 0]),
        "NORMAL": blob.add("3f", normals, vertices, "VEC3", 5126),
    }
    index = blob.add("I", indices, len(indices), "SCALAR", 5125)
    times = blob.add("f", [0.0, 1.0, 2.0], 3, "SCALAR", 5126, min=[0.0], max=[2.0])
    primitive = {"attributes": attributes, "indices": index}
    nodes, extra = [{"mesh": 0}], {}
    if kind == "skin":
        # Joint 1 takes the upper half: weight 0 below y = -0.1, 1 above y = 0.1.
        up = [min(1.0, max(0.0, (y + 0.1) / 0.2)) for y in positions[1::3]]
        attributes["JOINTS_0"] = blob.add("4B", [(0, 1, 0, 0)] * vertices, vertices, "VEC4", 5121)
        attributes["WEIGHTS_0"] = blob.add("4f", [(1 - w, w, 0.0, 0.0) for w in up], vertices, "VEC4", 5126)
        identity = (1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0)
        binds = blob.add("16f", [identity, identity], 2, "MAT4", 5126)
        s = math.sin(math.pi / 4)
        turns = blob.add("4f", [(0.0, 0.0, 0.0, 1.0), (s, 0.0, 0.0, s), (0.0, 0.0, 0.0, 1.0)], 3, "VEC4", 5126)
        nodes = [{"mesh": 0, "skin": 0}, {"children": [2]}, {}]
        extra["skins"] = [{"joints": [1, 2], "inverseBindMatrices": binds}]
        channel = {"sampler": 0, "target": {"node": 2, "path": "rotation"}}
        sampler = {"input": times, "output": turns}
    elif kind == "morph":
        xy = zip(positions[0::3], positions[1::3])
        bump = [(0.0, 0.0, 0.3 * math.sin(3 * math.pi * x) * math.sin(3 * math.pi * y)) for x, y in xy]
        lo = [min(b[k] for b in bump) for k in range(3)]
        hi = [max(b[k] for b in bump) for k in range(3)]
        primitive["targets"] = [{"POSITION": blob.add("3f", bump, len(bump), "VEC3", 5126, min=lo, max=hi)}]
        weights = blob.add("f", [0.0, 1.0, 0.0], 3, "SCALAR", 5126)
        channel = {"sampler": 0, "target": {"node": 0, "path": "weights"}}
        sampler = {"input": times, "output": weights}
    name = stem.rsplit("/", 1)[-1]
    animations = {"animations": [{"samplers": [sampler], "channels": [channel]}]} if kind != "still" else {}
    doc = {
        "asset": {"version": "2.0", "generator": "bench/deforming.py"},
        "buffers": [{"byteLength": len(blob.data), "uri": name + ".bin"}],
        "bufferViews": blob.views,
        "accessors": blob.accessors,
        "meshes": [{"primitives": [primitive], **({"weights": [0.0]} if kind == "morph" else {})}],
        "nodes": nodes,
        "scenes": [{"nodes": [0, 1] if kind == "skin" else [0]}],
        "scene": 0,
        **animations,
        **extra,
    }
    with open(stem + ".bin", "wb") as f:
        f.write(blob.data)
    with open(stem + ".gltf", "w") as f:
        json.dump(doc, f)
    print(f"{stem}.gltf: {kind}, {vertices} vertices, {len(indices) // 3} triangles")


if __name__ == "__main__":
    if len(sys.argv) != 4 or sys.argv[1] not in ("skin", "morph", "still"):
        sys.exit(__doc__)
    main(sys.argv[1], int(sys.argv[2]), sys.argv[3])
