#!/usr/bin/env python3
"""A K x K grid of unit quads as a glTF model, each quad with a material of its own colour, for
the large-file cases: with `primitives`, one mesh of K x K primitives (one per quad) in one
node; with `meshes`, K x K meshes of one primitive each, each in a node of its own, translated
to its place. The quads share one buffer view of four corners and six indices, so the file
grows with the JSON, not the geometry. Writes NAME.gltf and NAME.bin.

    python3 bench/many.py primitives 256 out/prims-65536
    python3 bench/many.py meshes 142 out/meshes-20164
"""

import json
import struct
import sys


def model(kind, k):
    corners = [0.0, 0.0, 0.0, 0.9, 0.0, 0.0, 0.9, 0.9, 0.0, 0.0, 0.9, 0.0]
    data = struct.pack("<12f", *corners) + struct.pack("<6H", 0, 1, 2, 0, 2, 3)
    views = [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12}]
    # One corner accessor and one index accessor per quad, all over the same views; a
    # primitives model moves each quad by its own corners (offset views would do it too, but
    # accessors' byteOffset keeps the buffer small).
    accessors, primitives, meshes, nodes, materials = [], [], [], [], []
    for q in range(k * k):
        x, y = q % k, q // k
        shifted = [c + (x if i % 3 == 0 else y if i % 3 == 1 else 0) for i, c in enumerate(corners)]
        if kind == "primitives":
            data += struct.pack("<12f", *shifted)
            views.append({"buffer": 0, "byteOffset": len(data) - 48, "byteLength": 48})
            position = len(accessors)
            accessors.append({"bufferView": len(views) - 1, "componentType": 5126, "count": 4, "type": "VEC3",
                              "min": [x, y, 0], "max": [x + 0.9, y + 0.9, 0]})
        else:
            position = 0
        materials.append({"pbrMetallicRoughness": {"baseColorFactor": [(x % 7) / 6, (y % 5) / 4, ((x + y) % 3) / 2, 1]},
                          "doubleSided": True})
        primitive = {"attributes": {"POSITION": position}, "indices": 1, "material": q}
        if kind == "primitives":
            primitives.append(primitive)
        else:
            meshes.append({"primitives": [primitive]})
            nodes.append({"mesh": q, "translation": [x, y, 0]})
    accessors[0:0] = [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                       "min": [0, 0, 0], "max": [0.9, 0.9, 0]},
                      {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}]
    if kind == "primitives":
        for p in primitives:
            p["attributes"]["POSITION"] += 2
        meshes, nodes = [{"primitives": primitives}], [{"mesh": 0}]
    gltf = {"asset": {"version": "2.0"}, "buffers": [{"byteLength": len(data)}], "bufferViews": views,
            "accessors": accessors, "materials": materials, "meshes": meshes, "nodes": nodes,
            "scenes": [{"nodes": list(range(len(nodes)))}], "scene": 0}
    return gltf, data


def main():
    kind, k, stem = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    if kind not in ("primitives", "meshes"):
        sys.exit("usage: many.py primitives|meshes K NAME")
    gltf, data = model(kind, k)
    gltf["buffers"][0]["uri"] = stem.split("/")[-1] + ".bin"
    with open(stem + ".bin", "wb") as f:
        f.write(data)
    with open(stem + ".gltf", "w") as f:
        json.dump(gltf, f)


if __name__ == "__main__":
    main()
