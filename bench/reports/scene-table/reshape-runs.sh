#!/bin/sh
# The Rust stages as plain entry points (spirv/rust) against the modules before (f5bdc9ac:spirv/rust,
# unpacked by `git archive f5bdc9ac spirv | tar x -C target/dev/old`), with `cargo xtask bundle`'s
# bundle copied to target/dev/after.tar.gz: run from the repository root with target/dev carried.
# The GLSL set (spirv/glsl) beside them: all three read from disk by one binary, so all three get the
# same specialisation. Run 1 names them glsl,new,old from place 0; run 2 old,new,glsl from 1000.
#   sh bench/reports/scene-table/reshape-runs.sh RUN LIMIT_SECONDS SCENE...
# (scenes not started past LIMIT_SECONDS; a second call with the same RUN goes on where it stopped)
set -u
[ -x /tmp/twinray-bench/bin/twinray ] || tar xzf target/dev/after.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib
run=$1 limit=$2
shift 2
start=$(date +%s)
if [ "$run" = 1 ]; then sets=spirv/glsl,spirv/rust,target/dev/old/spirv/rust; first=0
else sets=target/dev/old/spirv/rust,spirv/rust,spirv/glsl; first=1000; fi
mkdir -p $OUT/run$run /tmp/done
$B/bin/twinray info > $OUT/info.txt 2>&1
for scene in "$@"; do
  base=$(basename $scene)
  [ -e /tmp/done/$run-$base ] && continue
  if [ $(( $(date +%s) - start )) -gt "$limit" ]; then echo "stopped before $scene"; break; fi
  s=$(date +%s)
  $B/bin/twinray bench $scene --sets $sets --null --width 1920 --height 1080 --spp 1,16 --runs 10 \
    --warmup 2 --placements 1 --processes 4 --alone-in devices --first-placement $first \
    --reference-set spirv/glsl --reference-spp 16 --shadow-spp none --probes none --images none \
    --cache /tmp/refs --out $OUT/run$run/$base > $OUT/run$run/$base.log 2>&1
  echo "== run $run $scene: exit $?, $(( $(date +%s) - s )) s"
  grep " / " $OUT/run$run/$base.log | grep -v 'WARN\|wrote'
  touch /tmp/done/$run-$base
done
cd $OUT && tar czf run$run-$(date +%s).tgz run$run && rm -rf run$run
