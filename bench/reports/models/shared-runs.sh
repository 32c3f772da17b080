#!/bin/sh
# On the GPU machine: (1) shared BLASes against one BLAS per primitive (`--no-shared-blases`)
# on files whose meshes share: the same PNG byte for byte, the structures' count and memory, and
# the GPU time of ten traces; (2) both sets compared on every frame of assimp's simple_skin and
# AnimatedMorphCube; (3) the peak memory of a 2,000,000-triangle primitive
# (`bench/deforming.py still 1001`) against a 200-triangle one, three renders each, and of ten
# million triangles in one primitive (`still 2238`, 240 MB of buffer) once. Run from the
# repository root with target/dev/clip.tar.gz (`cargo xtask bundle --out target/dev/clip`),
# target/dev/many.tar.xz (`bench/many.py`, as large-runs.sh) and target/dev/models (the assimp
# files named below) carried; results under $OUT.
#   sh bench/reports/models/shared-runs.sh
set -u
[ -x /tmp/clip/bin/twinray ] || tar xzf target/dev/clip.tar.gz -C /tmp
export LD_LIBRARY_PATH=/tmp/clip/lib
T=/tmp/clip/bin/twinray
R=$OUT/shared
mkdir -p /tmp/many /tmp/sheets $R
tar xJf target/dev/many.tar.xz -C /tmp/many
$T info > $R/info.txt 2>&1
for f in /tmp/many/p16384.gltf /tmp/many/p65536.gltf target/dev/models/2CylinderEngine.glb \
  target/dev/models/AnimatedMorphCube.gltf; do
  b=$(basename $f)
  for flag in "" --no-shared-blases; do
    $T $flag render $f --width 1920 --height 1080 --runs 10 --out /tmp/$b$flag.png --json \
      > $R/$b$flag.json 2> $R/$b$flag.err
    echo "== $b $flag: exit $?"
    python3 -c "import json,sys; j=json.load(open(sys.argv[1])); a=j['acceleration_structures']; \
print(a['blases'], 'BLASes', a['instances'], 'instances', round(a['blas_bytes']/2**20,2), 'MiB', \
round(a['build_ms']), 'ms build; trace median', j.get('gpu_ms'), 'ms')" $R/$b$flag.json
  done
  cmp /tmp/$b.png /tmp/$b--no-shared-blases.png && echo "$b: the same PNG"
done
for model in simple_skin AnimatedMorphCube; do
  $T compare target/dev/models/$model.gltf --frames all --width 1920 --height 1080 --out-dir /tmp/cmp-$model \
    > $R/compare-$model.log 2>&1
  echo "== compare $model --frames all: exit $?"; tail -4 $R/compare-$model.log
done
python3 bench/deforming.py still 1001 /tmp/sheets/still-1001
python3 bench/deforming.py still 11 /tmp/sheets/still-11
for k in 1 2 3; do
  for n in 1001 11; do
    TWINRAY_MAX_MESH_BYTES=100000000 /usr/bin/time -v $T render /tmp/sheets/still-$n.gltf --width 1920 \
      --height 1080 --out /tmp/still.png > $R/still-$n-$k.log 2>&1
    echo "== still-$n ($k): exit $?"; grep -E "loaded|Maximum resident" $R/still-$n-$k.log
  done
done
python3 bench/deforming.py still 2238 /tmp/sheets/still-2238
TWINRAY_MAX_MESH_BYTES=400000000 /usr/bin/time -v $T render /tmp/sheets/still-2238.gltf --width 1920 --height 1080 \
  --out /tmp/still.png > $R/still-2238.log 2>&1
echo "== still-2238: exit $?"; grep -E "loaded|Maximum resident|Elapsed" $R/still-2238.log
cd $OUT && tar czf shared-$(date +%s).tgz shared && rm -rf shared
