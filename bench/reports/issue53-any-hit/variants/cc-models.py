"""Issue 53, eighteenth session: the ClearCoat model (Debian's assimp-testmodels) with some of
its features taken out, written beside it so that its textures resolve:
  CC-noblend.gltf  no material blended (no alpha masks: no any-hit stage runs)
  CC-noemit.gltf   no material emits (no emission)
  CC-plain.gltf    neither (textures only)
    python3 variants/cc-models.py target/models/ClearCoat-glTF/ClearCoatTest.gltf"""
import copy
import json
import os
import sys

source = sys.argv[1]
model = json.load(open(source))
for name, no_blend, no_emission in (("CC-noblend", True, False), ("CC-noemit", False, True), ("CC-plain", True, True)):
    variant = copy.deepcopy(model)
    for material in variant["materials"]:
        if no_blend:
            material.pop("alphaMode", None)
        if no_emission:
            material["emissiveFactor"] = [0, 0, 0]
            material.pop("emissiveTexture", None)
    json.dump(variant, open(os.path.join(os.path.dirname(source), name + ".gltf"), "w"))
