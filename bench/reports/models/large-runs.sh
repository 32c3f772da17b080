#!/bin/sh
# Files of many meshes and many primitives on the GPU machine: each of target/dev/many.tar.xz
# (`python3 bench/many.py primitives 128|256` and `meshes 71|142`: one mesh of 16,384 or
# 65,536 primitives, or 5,041 or 20,164 meshes, each quad with a material of its own)
# compared Rust against GLSL at 1920x1080, then rendered alone three times for its load and
# build times and peak memory. Run from the repository root with target/dev/clip.tar.gz and
# target/dev/many.tar.xz carried (the bundle of `cargo xtask bundle --out target/dev/clip`).
#   sh bench/reports/models/large-runs.sh
set -u
[ -x /tmp/clip/bin/twinray ] || tar xzf target/dev/clip.tar.gz -C /tmp
export LD_LIBRARY_PATH=/tmp/clip/lib
T=/tmp/clip/bin/twinray
mkdir -p /tmp/many $OUT/large
tar xJf target/dev/many.tar.xz -C /tmp/many
$T info > $OUT/large/info.txt 2>&1
for f in p16384 p65536 m5041 m20164; do
  echo "== $f"
  $T compare /tmp/many/$f.gltf --width 1920 --height 1080 --out-dir /tmp/cmp-$f > $OUT/large/$f-compare.log 2>&1
  echo "compare exit $?"; grep -E "hit mismatches|PASS|FAIL" $OUT/large/$f-compare.log
  for k in 1 2 3; do
    /usr/bin/time -v $T render /tmp/many/$f.gltf --width 1920 --height 1080 --out /tmp/$f.png \
      > $OUT/large/$f-render$k.log 2>&1 || $T render /tmp/many/$f.gltf --width 1920 --height 1080 \
      --out /tmp/$f.png > $OUT/large/$f-render$k.log 2>&1
    grep -E "loaded|Maximum resident|Elapsed" $OUT/large/$f-render$k.log
  done
done
cd $OUT && tar czf large-$(date +%s).tgz large && rm -rf large
