#!/bin/sh
# On the GPU machine: a model of several animations played together as glTF-Sample-Viewer
# starts them (`bench/animations.py`: three quads, each moved by an animation of its own, a
# fourth animation left out as it drives what the first drives), alone and with a
# KHR_animation_pointer channel beside its nodes' channels; both sets compared on every frame
# at 8 frames a second at 1920x1080, and stills at 0 s and 3 s. Run from the repository root
# with target/dev/clip.tar.gz carried (`cargo xtask bundle --out target/dev/clip`); results
# under $OUT.
#   sh bench/reports/models/several-runs.sh
set -u
[ -x /tmp/clip/bin/twinray ] || tar xzf target/dev/clip.tar.gz -C /tmp
export LD_LIBRARY_PATH=/tmp/clip/lib
T=/tmp/clip/bin/twinray
R=$OUT/several
mkdir -p /tmp/several $R
$T info > $R/info.txt 2>&1
for kind in plain pointer; do
  python3 bench/animations.py $kind /tmp/several/$kind
  $T --fps 8 compare /tmp/several/$kind.gltf --width 1920 --height 1080 --frames all --out-dir /tmp/cmp-$kind \
    > $R/compare-$kind.log 2>&1
  echo "== compare $kind --frames all: exit $?"; head -2 $R/compare-$kind.log; tail -3 $R/compare-$kind.log
done
for t in 0 3; do
  $T --time $t render /tmp/several/plain.gltf --width 1920 --height 1080 --out $R/plain-$t.png > $R/render-$t.log 2>&1
  echo "== render --time $t: exit $?"; tail -2 $R/render-$t.log
done
cd $OUT && tar czf several-$(date +%s).tgz several && rm -rf several
