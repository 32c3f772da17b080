#!/bin/sh
# Textured models and the million-triangle scene on the GPU: what each load and build takes,
# then Rust against GLSL over placements with the null control, in both label orders.
here=$(cd "$(dirname "$0")/.." && pwd)
export LD_LIBRARY_PATH="$here/lib"
T="$here/bin/twinray"
cd "$here/models"
$T info | head -6
SCENES="BoxTextured.glb TextureTransformTest.gltf floor.toml masked.toml instanced.toml separate.toml"
for s in $SCENES; do
  printf '%s ' "$s"
  $T render "$s" --width 1920 --height 1080 --json --runs 1 --warmup 0 --out "/tmp/$s.png" 2>/dev/null |
    python3 -c "import json,sys; d=json.load(sys.stdin); print(json.dumps({'load_ms': d['load_ms'], 'accel': d['acceleration_structures']}))"
done
COMMON="--width 1920 --height 1080 --spp 16 --runs 10 --warmup 3 --placements 6 --null --reference-spp 256 --shadow-spp none --probes none --images none --cache /tmp/refs"
$T bench $SCENES $COMMON --sets rust,glsl --out "$OUT/rust-glsl" 2>&1 | grep -v WARN | tail -30
$T bench $SCENES $COMMON --sets glsl,rust --out "$OUT/glsl-rust" 2>&1 | grep -v WARN | tail -30
