#!/bin/sh
# Issue 53: does running spirv-opt -O over a set change its time? Each scene at 1920x1080 and
# 16 spp with the built-in sets and the same modules through `spirv-opt -O` (target/opt-sets,
# made by opt-sets.sh), every set alone on ROUNDS fresh devices.
#   sh bench/reports/issue53-opt/device.sh ROUNDS SCENE...
set -u
tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
T=$B/bin/twinray
rounds=$1
shift
R=$OUT/opt
mkdir -p $R
$T info > $R/info.txt 2>&1
for scene in "$@"; do
  s=$(date +%s)
  out=$R/$(basename $scene)
  $T bench $scene --sets glsl,rust,target/opt-sets/rust,target/opt-sets/glsl --width 1920 --height 1080 \
    --spp 16 --runs 10 --warmup 2 --placements 1 --processes $rounds --alone-in devices \
    --reference-spp 16 --shadow-spp none --probes none --images none --cache /tmp/refs --out $out > $out.log 2>&1
  echo "== $scene: exit $?, $(( $(date +%s) - s )) s"
  grep "/" $out.log | grep -v 'WARN\|wrote'
done
cd $OUT && tar czf opt.tgz $(find opt -name results.json -o -name '*.txt' -o -name '*.log') && rm -rf opt
