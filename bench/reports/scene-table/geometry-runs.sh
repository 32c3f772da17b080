#!/bin/sh
# The stages of contract 0.3.0 (mesh hits reading their object as instance id plus geometry
# index, a glTF mesh's primitives in one BLAS; point lights dimmed by their range and cone)
# against the modules before them (c1f3bc0d:spirv, unpacked by
# `git archive c1f3bc0d spirv | tar x -C target/dev/pregeometry` and restamped to contract
# 0.3.0 with `perl -pi -e 's/twinray-shared 0\.2\.0/twinray-shared 0.3.0/g'`, the record alone
# differing), both languages, in one binary from `cargo xtask bundle --out target/dev/clip`: run
# from the repository root with target/dev/clip.tar.gz and target/dev/pregeometry carried.
# The old modules read a mesh hit's object as the instance id alone, right only where no BLAS
# holds two meshes: scenes whose objects all lie apart (the built-in ones). A scene named with
# `new:` (a glTF model, whose primitives now share BLASes) is timed with the new sets alone.
# Run 1 names new rust, old rust, new glsl, old glsl from place 0; run 2 the reverse from 1000.
#   sh bench/reports/scene-table/geometry-runs.sh RUN LIMIT_SECONDS SCENE|new:SCENE...
set -u
[ -x /tmp/clip/bin/twinray ] || tar xzf target/dev/clip.tar.gz -C /tmp
export LD_LIBRARY_PATH=/tmp/clip/lib
T=/tmp/clip/bin/twinray
old=target/dev/pregeometry/spirv
run=$1 limit=$2
shift 2
start=$(date +%s)
mkdir -p $OUT/geometry$run /tmp/done
$T info > $OUT/geometry$run/info.txt 2>&1
for arg in "$@"; do
  scene=${arg#new:}
  if [ "$arg" != "$scene" ]; then
    if [ "$run" = 1 ]; then sets=spirv/rust,spirv/glsl; else sets=spirv/glsl,spirv/rust; fi
  elif [ "$run" = 1 ]; then sets=spirv/rust,$old/rust,spirv/glsl,$old/glsl
  else sets=$old/glsl,spirv/glsl,$old/rust,spirv/rust; fi
  if [ "$run" = 1 ]; then first=0; else first=1000; fi
  base=$(basename $scene)
  [ -e /tmp/done/$run-$base ] && continue
  if [ $(( $(date +%s) - start )) -gt "$limit" ]; then echo "stopped before $scene"; break; fi
  s=$(date +%s)
  $T bench $scene --sets $sets --null --width 1920 --height 1080 --spp 1,16 --runs 10 \
    --warmup 2 --placements 1 --processes 4 --alone-in devices --first-placement $first \
    --reference-set spirv/glsl --reference-spp 16 --shadow-spp none --probes none --images none \
    --cache /tmp/refs --out $OUT/geometry$run/$base > $OUT/geometry$run/$base.log 2>&1
  echo "== run $run $scene: exit $?, $(( $(date +%s) - s )) s"
  grep " / " $OUT/geometry$run/$base.log | grep -v 'WARN\|wrote'
  touch /tmp/done/$run-$base
done
cd $OUT && tar czf geometry$run-$(date +%s).tgz geometry$run && rm -rf geometry$run
