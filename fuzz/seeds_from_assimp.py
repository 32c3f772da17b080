"""Seeds for the `gltf` fuzz target from Debian's assimp-testmodels (models nobody here wrote):
every glTF 2.0 model under /usr/share/assimp/models/glTF2 of at most 400 KB, made
self-contained, since the fuzz target reads no files: a .gltf's buffers and images become one
GLB's binary chunk (a file that is missing keeps its URI, as a hostile model would); a .glb is
copied. Writes fuzz/corpus/gltf/assimp-NAME.glb (.gltf where the JSON is kept).
    python3 fuzz/seeds_from_assimp.py [MODELS] [OUT]"""
import base64
import json
import os
import struct
import sys

MODELS = sys.argv[1] if len(sys.argv) > 1 else "/usr/share/assimp/models/glTF2"
OUT = sys.argv[2] if len(sys.argv) > 2 else os.path.join(os.path.dirname(__file__), "corpus", "gltf")
LIMIT = 400_000


def read_uri(folder, uri):
    if uri.startswith("data:"):
        return base64.b64decode(uri.split(",", 1)[1])
    path = os.path.join(folder, uri.replace("%20", " "))
    return open(path, "rb").read() if os.path.isfile(path) else None


def glb(doc, bin_chunk):
    def padded(data, fill):
        return data + fill * ((4 - len(data) % 4) % 4)
    js = padded(json.dumps(doc, separators=(",", ":")).encode(), b" ")
    out = struct.pack("<II", len(js), 0x4E4F534A) + js
    if bin_chunk:
        b = padded(bin_chunk, b"\0")
        out += struct.pack("<II", len(b), 0x004E4942) + b
    return struct.pack("<4sII", b"glTF", 2, 12 + len(out)) + out


def embed(path):
    folder = os.path.dirname(path)
    doc = json.load(open(path, encoding="utf-8"))
    data, starts = bytearray(), {}
    for i, buffer in enumerate(doc.get("buffers", [])):
        content = read_uri(folder, buffer["uri"]) if "uri" in buffer else None
        if content is None:
            continue
        data += b"\0" * ((8 - len(data) % 8) % 8)
        starts[i] = len(data)
        data += content
    if len(starts) != len(doc.get("buffers", [])):
        return None  # a missing file: the JSON as it is covers that case better
    views = doc.get("bufferViews", [])
    for view in views:
        view["byteOffset"] = view.get("byteOffset", 0) + starts[view["buffer"]]
        view["buffer"] = 0
    for image in doc.get("images", []):
        content = read_uri(folder, image["uri"]) if "uri" in image else None
        if content is None:
            continue
        data += b"\0" * ((8 - len(data) % 8) % 8)
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(content)})
        data += content
        image["bufferView"] = len(views) - 1
        image["mimeType"] = "image/jpeg" if image["uri"].lower().endswith((".jpg", ".jpeg")) else "image/png"
        del image["uri"]
    if views:
        doc["bufferViews"] = views
    doc["buffers"] = [{"byteLength": len(data)}] if data else []
    return glb(doc, bytes(data))


def main():
    os.makedirs(OUT, exist_ok=True)
    written = 0
    for root, _, files in sorted(os.walk(MODELS)):
        for name in sorted(files):
            path = os.path.join(root, name)
            if name.endswith(".glb"):
                out = open(path, "rb").read()
            elif name.endswith(".gltf"):
                try:
                    out = embed(path)
                except (ValueError, KeyError, TypeError, UnicodeDecodeError):
                    out = None
                out = out if out is not None else open(path, "rb").read()
            else:
                continue
            if len(out) > LIMIT:
                continue
            stem = os.path.relpath(path, MODELS).replace("/", "-").rsplit(".", 1)[0]
            suffix = "glb" if out.startswith(b"glTF") else "gltf"
            open(os.path.join(OUT, f"assimp-{stem}.{suffix}"), "wb").write(out)
            written += 1
    print(f"{written} seeds in {OUT}")


main()
