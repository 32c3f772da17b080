#!/bin/sh
# NVIDIA check of textures on procedural shapes: Rust against GLSL on the textured shapes
# (level 0, and ray cones with the image tiled), then the bench: the textured shapes, Rust
# against GLSL; and the untextured procedural scenes, each set against its own modules from
# before the change (old/: spirv/ of 81abb88), to see what the texture code costs shapes
# that have none.
here=$(cd "$(dirname "$0")/.." && pwd)
export LD_LIBRARY_PATH="$here/lib"
T="$here/bin/twinray"
cd "$here/models"
$T info | head -4
for s in shapes.toml cones.toml showcase; do
  printf '%s: ' "$s"
  $T compare "$s" --a rust --b glsl --width 1920 --height 1080 --json --out-dir "$OUT/cmp-$s" 2>/dev/null |
    python3 -c "import json,sys; d=json.load(sys.stdin); print('rmse', d['rmse'], 'hit_mismatches', d['hit_mismatches'], 'pass', d['pass'])"
done
$T render cones.toml --shaders rust --width 960 --height 540 --out "$OUT/cones-rust.png" 2>&1 | tail -1
COMMON="--width 1920 --height 1080 --spp 16 --runs 10 --warmup 3 --placements 6 --null --reference-spp 256 --shadow-spp none --probes none --images none --cache /tmp/refs"
$T bench shapes.toml cones.toml $COMMON --sets rust,glsl --out "$OUT/shapes" 2>&1 | grep -v WARN | tail -12
$T bench sphere showcase swarm $COMMON --sets rust,$here/old/rust --out "$OUT/rust-old" 2>&1 | grep -v WARN | tail -12
$T bench sphere showcase swarm $COMMON --sets glsl,$here/old/glsl --out "$OUT/glsl-old" 2>&1 | grep -v WARN | tail -12
