#!/bin/sh
# Refit against rebuild for meshes that deform (skins, morph targets): `bench/deforming.py`'s
# sheets of 724 x 724 vertices (1.04 million triangles), bent by a joint or raised by a morph
# target over 25 frames (to the clip's widest pose, 1 s), each frame's BLAS refitted in place
# (update) or built afresh (rebuild), with the trace time of each; then both sets compared on
# every frame of assimp's simple_skin and AnimatedMorphCube, and a still sheet of ten million
# triangles rendered once. Run from the repository root with
# `cargo xtask bundle --out target/dev/clip`'s target/dev/clip.tar.gz (and the two models under
# target/dev/models) carried; results under $OUT.
set -u
[ -x /tmp/clip/bin/twinray ] || tar xzf target/dev/clip.tar.gz -C /tmp
export LD_LIBRARY_PATH=/tmp/clip/lib
T=/tmp/clip/bin/twinray
mkdir -p $OUT/deforming /tmp/sheets
$T info > $OUT/deforming/info.txt 2>&1
for kind in skin morph; do
  python3 bench/deforming.py $kind 724 /tmp/sheets/$kind-724
  s=$(date +%s)
  $T animate-bench /tmp/sheets/$kind-724.gltf --modes rebuild,update --frames 25 --width 1920 --height 1080 \
    --runs 5 --placements 3 --out $OUT/deforming/$kind > $OUT/deforming/$kind.log 2>&1
  echo "== $kind: exit $?, $(( $(date +%s) - s )) s"
  grep '^|' $OUT/deforming/$kind.log
done
for model in simple_skin AnimatedMorphCube; do
  $T compare target/dev/models/$model.gltf --frames all --width 1920 --height 1080 --out-dir /tmp/cmp-$model \
    > $OUT/deforming/compare-$model.log 2>&1
  echo "== compare $model: exit $?"; tail -3 $OUT/deforming/compare-$model.log
done
# Ten million triangles in one primitive (2238 x 2238 vertices with normals, 240 MB of buffer):
# load and build time, BLAS memory, and the process's peak.
python3 bench/deforming.py still 2238 /tmp/sheets/still-2238
TIME=$(command -v /usr/bin/time >/dev/null && echo "/usr/bin/time -v" || echo "")
TWINRAY_MAX_MESH_BYTES=400000000 $TIME $T render /tmp/sheets/still-2238.gltf --width 1920 --height 1080 \
  --out /tmp/still.png > $OUT/deforming/still-2238.log 2>&1
echo "== still-2238: exit $?"; grep -i "loaded\|Maximum resident\|Elapsed" $OUT/deforming/still-2238.log
cd $OUT && tar czf deforming.tgz deforming && rm -rf deforming
