#!/bin/sh
# Issue 53: both sets with the branch-free payload check against both as they were before
# (target/old-sets), every set alone on ROUNDS fresh devices at 1920x1080. Run
# from the repository root with the bundle.
#   sh bench/reports/issue53-branches/device-landed.sh NAME ROUNDS SPP SCENE...
set -u
[ -x /tmp/twinray-bench/bin/twinray ] || tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
T=$B/bin/twinray
name=$1 rounds=$2 spp=$3
shift 3
R=$OUT/$name
mkdir -p $R
$T info > $R/info.txt 2>&1
for scene in "$@"; do
  s=$(date +%s)
  out=$R/$(basename $scene)
  $T bench $scene --sets glsl,rust,target/old-sets/glsl,target/old-sets/rust --width 1920 --height 1080 \
    --spp $spp --runs 10 --warmup 2 --placements 1 --processes $rounds --alone-in devices \
    --reference-spp 16 --shadow-spp none --probes none --images none --cache /tmp/refs --out $out > $out.log 2>&1
  echo "== $scene: exit $?, $(( $(date +%s) - s )) s"
  grep " / " $out.log | cut -c1-130
done
cd $OUT && tar czf $name.tgz $(find $name -name results.json -o -name '*.txt' -o -name '*.log') && rm -rf $name
