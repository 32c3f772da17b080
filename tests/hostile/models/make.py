#!/usr/bin/env python3
"""Writes this folder's hostile glTF models, each one square (two triangles) with one fault
of a class the glTF loader refuses: python3 tests/hostile/models/make.py. The files are committed;
tests/hostile/cases.json says what each must be refused with."""
import base64
import json
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
SQUARE = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.0, 0.0)]


def data_uri(data, mime="application/octet-stream"):
    return "data:%s;base64,%s" % (mime, base64.b64encode(data).decode())


def square():
    """The square's document: positions (view 0), u16 indices (view 1), as Python objects."""
    positions = b"".join(struct.pack("<3f", *p) for p in SQUARE)
    indices = struct.pack("<6H", 0, 1, 2, 0, 2, 3)
    data = positions + indices
    return {
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": len(data), "uri": data_uri(data)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 48},
            {"buffer": 0, "byteOffset": 48, "byteLength": 12},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    }


def png_claiming(width, height):
    """A 1x1 PNG whose header says `width` x `height` (its checksum made right)."""
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    header = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    pixels = zlib.compress(b"\0" + b"\0" * 4)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", pixels) + chunk(b"IEND", b"")


def textured(image):
    doc = square()
    uvs = b"".join(struct.pack("<2f", p[0], p[1]) for p in SQUARE)
    data = base64.b64decode(doc["buffers"][0]["uri"].split(",")[1]) + uvs
    doc["buffers"][0] = {"byteLength": len(data), "uri": data_uri(data)}
    doc["bufferViews"].append({"buffer": 0, "byteOffset": 60, "byteLength": 32})
    doc["accessors"].append({"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"})
    doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 2
    doc["meshes"][0]["primitives"][0]["material"] = 0
    doc["images"] = [image]
    doc["textures"] = [{"source": 0}]
    doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    return doc


def models():
    out = {}
    doc = square()
    doc["bufferViews"][0]["byteStride"] = 8
    out["stride-short"] = doc
    doc = square()
    doc["accessors"][0].update({"count": 3, "byteOffset": 2})
    out["offset-misaligned"] = doc
    doc = square()
    doc["meshes"].insert(0, {"primitives": []})
    doc["nodes"][0]["mesh"] = 0
    out["mesh-no-primitives"] = doc
    doc = square()
    doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 7
    out["position-missing-accessor"] = doc
    for name, indices, count in [("sparse-past-end", (4, 0), 1), ("sparse-not-rising", (2, 0), 2)]:
        doc = square()
        extra = struct.pack("<2H", *indices) + b"".join(struct.pack("<3f", 2.0, 2.0, 0.0) for _ in range(count))
        data = base64.b64decode(doc["buffers"][0]["uri"].split(",")[1]) + extra
        doc["buffers"][0] = {"byteLength": len(data), "uri": data_uri(data)}
        doc["bufferViews"] += [
            {"buffer": 0, "byteOffset": 60, "byteLength": 4},
            {"buffer": 0, "byteOffset": 64, "byteLength": 12 * count},
        ]
        doc["accessors"][0]["max"] = [2, 2, 0]
        doc["accessors"][0]["sparse"] = {
            "count": count,
            "indices": {"bufferView": 2, "componentType": 5123},
            "values": {"bufferView": 3},
        }
        out[name] = doc
    out["png-header-huge"] = textured({"uri": data_uri(png_claiming(16384, 16384), "image/png")})
    doc = textured({"bufferView": 0})
    out["image-view-without-mime-type"] = doc
    doc = square()
    doc["buffers"][0]["uri"] = "/etc/passwd"
    out["buffer-absolute-path"] = doc
    doc = square()
    doc["buffers"][0]["uri"] = "../../../../../../../../etc/passwd"
    out["buffer-up-and-out"] = doc
    doc = square()
    doc["buffers"][0]["uri"] = "%2E%2E/%2E%2E/%2E%2E/%2E%2E/etc/passwd"
    out["buffer-escaped-up-and-out"] = doc
    return out


for name, doc in models().items():
    with open(os.path.join(HERE, name + ".gltf"), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")
