#!/bin/sh
# The table of bench/reports/textures-h100 on lavapipe at a smaller size: the same scenes
# (that report's models/ and three of assimp-testmodels'), what each load and build takes,
# then Rust against GLSL over placements with the null control, in both label orders.
# Run from the repository root after `cargo build --release -p twinray`; OUT is where the
# benches write (default target/textures-lavapipe).
set -e
root=$(pwd)
T="$root/target/release/twinray"
OUT=${OUT:-$root/target/textures-lavapipe}
work="$OUT/models"
mkdir -p "$work"
cp "$root"/bench/reports/textures-h100/models/* "$work"/
A=/usr/share/assimp/models/glTF2
cp "$A/BoxTextured-glTF-Binary/BoxTextured.glb" "$A/2CylinderEngine-glTF-Binary/2CylinderEngine.glb" "$work"/
cp "$A"/textureTransform/* "$work"/
cd "$work"
$T info | head -6
SCENES="BoxTextured.glb TextureTransformTest.gltf floor.toml masked.toml instanced.toml separate.toml"
for s in $SCENES; do
  printf '%s ' "$s"
  $T render "$s" --width 480 --height 270 --json --runs 1 --warmup 0 --out "$OUT/$s.png" 2>/dev/null |
    python3 -c "import json,sys; d=json.load(sys.stdin); print(json.dumps({'load_ms': d['load_ms'], 'accel': d['acceleration_structures']}))"
done
COMMON="--width 480 --height 270 --spp 4 --runs 10 --warmup 1 --placements 4 --null --reference-spp 64 --shadow-spp none --probes none --images none --cache $OUT/refs"
$T bench $SCENES $COMMON --sets rust,glsl --out "$OUT/rust-glsl" 2>&1 | grep -v WARN | tail -30
$T bench $SCENES $COMMON --sets glsl,rust --out "$OUT/glsl-rust" 2>&1 | grep -v WARN | tail -30
