#!/bin/sh
# The ray generation stages with orthographic cameras (964b8dc1: a branch on FrameUniform.cone.y
# before the perspective camera) against the modules before them (40253b4a:spirv, unpacked by
# `git archive 40253b4a spirv | tar x -C target/dev/preortho` and restamped to contract 0.2.0
# with `perl -pi -e 's/twinray-shared 0\.1\.0/twinray-shared 0.2.0/g'`, the record alone
# differing), both languages, in one binary from `cargo xtask bundle --out target/dev/clip`:
# run from the repository root with target/dev/clip.tar.gz and target/dev/preortho carried.
# Run 1 names new rust, old rust, new glsl, old glsl from place 0; run 2 the reverse from 1000.
#   sh bench/reports/scene-table/camera-runs.sh RUN LIMIT_SECONDS SCENE...
set -u
[ -x /tmp/clip/bin/twinray ] || tar xzf target/dev/clip.tar.gz -C /tmp
export LD_LIBRARY_PATH=/tmp/clip/lib
T=/tmp/clip/bin/twinray
old=target/dev/preortho/spirv
run=$1 limit=$2
shift 2
start=$(date +%s)
if [ "$run" = 1 ]; then sets=spirv/rust,$old/rust,spirv/glsl,$old/glsl; first=0
else sets=$old/glsl,spirv/glsl,$old/rust,spirv/rust; first=1000; fi
mkdir -p $OUT/camera$run /tmp/done
$T info > $OUT/camera$run/info.txt 2>&1
for scene in "$@"; do
  base=$(basename $scene)
  [ -e /tmp/done/$run-$base ] && continue
  if [ $(( $(date +%s) - start )) -gt "$limit" ]; then echo "stopped before $scene"; break; fi
  s=$(date +%s)
  $T bench $scene --sets $sets --null --width 1920 --height 1080 --spp 1,16 --runs 10 \
    --warmup 2 --placements 1 --processes 4 --alone-in devices --first-placement $first \
    --reference-set spirv/glsl --reference-spp 16 --shadow-spp none --probes none --images none \
    --cache /tmp/refs --out $OUT/camera$run/$base > $OUT/camera$run/$base.log 2>&1
  echo "== run $run $scene: exit $?, $(( $(date +%s) - s )) s"
  grep " / " $OUT/camera$run/$base.log | grep -v 'WARN\|wrote'
  touch /tmp/done/$run-$base
done
cd $OUT && tar czf camera$run-$(date +%s).tgz camera$run && rm -rf camera$run
