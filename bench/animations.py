#!/usr/bin/env python3
"""A glTF model of three quads and four animations, as files in the wild animate one object
per animation: 0 moves quad 0 across (2 s), 1 lifts quad 1 (4 s), 2 moves quad 0 again (so a
viewer that starts every animation driving nothing an earlier one drives leaves it out), 3
spins quad 2 (3 s); with `pointer`, animation 1 also fades a material's colour through
KHR_animation_pointer. For `twinray compare --frames all` on a GPU: every animation played
must move its quad in both sets alike. Writes NAME.gltf with its buffer embedded.

    python3 bench/animations.py plain out/animations
"""

import base64
import json
import math
import struct
import sys


def floats(values):
    """Little-endian floats of scalars or of lists of them."""
    flat = [x for v in values for x in (v if isinstance(v, list) else [v])]
    return struct.pack("<%df" % len(flat), *flat)


def model(pointer):
    views, accessors, blobs = [], [], []

    def add(data, count, kind, **extra):
        """Appends `data` as a buffer view and an accessor of it; returns the accessor's index."""
        views.append({"buffer": 0, "byteOffset": sum(map(len, blobs)), "byteLength": len(data)})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5126, "count": count, "type": kind})
        accessors[-1].update(extra)
        blobs.append(data)
        return len(accessors) - 1

    quad = [[-0.5, -0.5, 0.0], [0.5, -0.5, 0.0], [0.5, 0.5, 0.0], [-0.5, 0.5, 0.0]]
    position = add(floats(quad), 4, "VEC3", min=[-0.5, -0.5, 0.0], max=[0.5, 0.5, 0.0])
    indices = add(struct.pack("<6H", 0, 1, 2, 0, 2, 3), 6, "SCALAR", componentType=5123)

    def keys(times):
        return add(floats(times), len(times), "SCALAR", min=[times[0]], max=[times[-1]])

    def values(v, kind):
        return add(floats(v), len(v), kind)

    spin = [[0.0, 0.0, math.sin(a / 2), math.cos(a / 2)] for a in (0.0, math.pi, 2 * math.pi)]
    two, four, three = keys([0.0, 2.0]), keys([0.0, 4.0]), keys([0.0, 1.5, 3.0])

    def animation(times, output, node, path):
        return {"samplers": [{"input": times, "output": output}],
                "channels": [{"sampler": 0, "target": {"node": node, "path": path}}]}

    animations = [
        animation(two, values([[-2.0, 1.0, 0.0], [2.0, 1.0, 0.0]], "VEC3"), 0, "translation"),
        animation(four, values([[0.0, -1.5, 0.0], [0.0, 0.5, 0.0]], "VEC3"), 1, "translation"),
        animation(two, values([[9.0, 9.0, 9.0], [9.0, 9.0, 9.0]], "VEC3"), 0, "translation"),
        animation(three, values(spin, "VEC4"), 2, "rotation"),
    ]
    doc = {"asset": {"version": "2.0"}}
    if pointer:
        doc["extensionsUsed"] = ["KHR_animation_pointer"]
        fade = values([[1.0, 1.0, 1.0, 1.0], [0.2, 0.2, 1.0, 1.0]], "VEC4")
        animations[1]["samplers"].append({"input": four, "output": fade})
        target = {"path": "pointer", "extensions": {"KHR_animation_pointer": {
            "pointer": "/materials/0/pbrMetallicRoughness/baseColorFactor"}}}
        animations[1]["channels"].append({"sampler": 1, "target": target})
    blob = b"".join(blobs)
    doc.update({
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
        "bufferViews": views, "accessors": accessors,
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0]}, "doubleSided": True}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": position}, "indices": indices, "material": 0}]}],
        "nodes": [{"mesh": 0}, {"mesh": 0}, {"mesh": 0, "translation": [2.0, -1.0, 0.0]}],
        "scenes": [{"nodes": [0, 1, 2]}],
        "animations": animations,
    })
    return doc


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] not in ("plain", "pointer"):
        sys.exit(__doc__)
    with open(sys.argv[2] + ".gltf", "w") as f:
        json.dump(model(sys.argv[1] == "pointer"), f)
