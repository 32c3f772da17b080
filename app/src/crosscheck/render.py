"""Renders the Mitsuba passes `twinray crosscheck` wrote (docs/shading-model.md).

    python render.py MANIFEST.json

MANIFEST names the variant, the samples per pixel and the passes, each a Mitsuba scene
dictionary in JSON beside it. Two rules turn JSON into what `mitsuba.load_dict` takes: a
`to_world` that is a 4 x 4 nested list (row-major) becomes a `ScalarTransform4f`, and one
that is `{"look_at": {...}}` becomes `ScalarTransform4f().look_at(...)`; a `filename` is
relative to the manifest's folder. Each pass is rendered twice, with half the samples and
seeds 1 and 2 (twinray estimates Mitsuba's noise from the two), to NAME.a.f32 and
NAME.b.f32: float32 RGBA, row by row from the top, little-endian."""
import json
import os
import sys
import time

import mitsuba as mi
import numpy as np


def load(value, folder):
    if isinstance(value, dict):
        out = {}
        for key, item in value.items():
            if key == "to_world" and isinstance(item, dict) and "look_at" in item:
                out[key] = mi.ScalarTransform4f().look_at(**item["look_at"])
            elif key == "to_world" and isinstance(item, list):
                out[key] = mi.ScalarTransform4f(item)
            elif key == "filename":
                out[key] = os.path.join(folder, item)
            else:
                out[key] = load(item, folder)
        return out
    return value


def main():
    manifest_path = sys.argv[1]
    folder = os.path.dirname(os.path.abspath(manifest_path))
    with open(manifest_path) as f:
        manifest = json.load(f)
    mi.set_variant(manifest["variant"])
    half = manifest["spp"] // 2
    for name in manifest["passes"]:
        with open(os.path.join(folder, name + ".json")) as f:
            scene = mi.load_dict(load(json.load(f), folder))
        for seed, part in [(1, "a"), (2, "b")]:
            start = time.time()
            image = np.array(mi.render(scene, seed=seed, spp=half), dtype="<f4")
            image.tofile(os.path.join(folder, f"{name}.{part}.f32"))
            print(f"  mitsuba {manifest['scene']} {name}.{part}: {half} spp in {time.time() - start:.1f} s", flush=True)


if __name__ == "__main__":
    main()
