#!/bin/sh
# NVIDIA check of this tree: Rust against GLSL on the textured scenes (emission, OBJ with MTL
# textures, the fuzz seed), then the bench of four textured scenes, one label order.
here=$(cd "$(dirname "$0")/.." && pwd)
export LD_LIBRARY_PATH="$here/lib"
T="$here/bin/twinray"
cd "$here/models"
$T info | head -4
for s in BoxTextured.glb TextureTransformTest.gltf floor.toml masked.toml emissive.toml spider.obj seed.gltf; do
  printf '%s: ' "$s"
  $T compare "$s" --a rust --b glsl --width 1920 --height 1080 --json --out-dir "$OUT/cmp-$s" 2>/dev/null |
    python3 -c "import json,sys; d=json.load(sys.stdin); print('rmse', d['rmse'], 'hit_mismatches', d['hit_mismatches'], 'pass', d['pass'])"
done
$T render emissive.toml --shaders rust --width 480 --height 270 --out "$OUT/emissive-rust.png" 2>&1 | tail -1
$T render spider.obj --shaders rust --out "$OUT/spider-rust.png" 2>&1 | tail -1
COMMON="--width 1920 --height 1080 --spp 16 --runs 10 --warmup 3 --placements 6 --null --reference-spp 256 --shadow-spp none --probes none --images none --cache /tmp/refs"
$T bench BoxTextured.glb floor.toml masked.toml emissive.toml $COMMON --sets rust,glsl --out "$OUT/rust-glsl" 2>&1 | grep -v WARN | tail -20
