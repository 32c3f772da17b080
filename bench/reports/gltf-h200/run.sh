#!/bin/sh
# glTF and compaction on the GPU: what each render reports, and Rust against GLSL.
here=$(cd "$(dirname "$0")/.." && pwd)
export LD_LIBRARY_PATH="$here/lib"
T="$here/bin/twinray"
cd "$here/models"
$T info | head -5
for s in 2CylinderEngine.glb BoxTextured.glb instanced.toml separate.toml; do
  echo "== render $s"
  $T render $s --width 1920 --height 1080 --runs 10 --warmup 3 --out "$OUT/$s.png" 2>&1 | grep -v WARN
  $T render $s --width 1920 --height 1080 --json --out "$OUT/$s-json.png" 2>/dev/null | python3 -c "import json,sys; d=json.load(sys.stdin); print(d['acceleration_structures'], d['load_ms'])" 2>&1
  echo "== compare $s"
  $T compare $s --width 1920 --height 1080 --out-dir "$OUT/cmp-$s" 2>&1 | grep -v WARN | tail -9
done
