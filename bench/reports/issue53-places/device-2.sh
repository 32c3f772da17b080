#!/bin/sh
# Issue 53, second run: does the place's effect on code depend on how the pipeline is made
# (linked from libraries, the default on NVIDIA, or monolithic), and on whether the spacers
# are salted? Then bench's rounds of places with monolithic pipelines.
#   sh bench/reports/issue53-places/device-2.sh SECONDS
set -u
tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
T=$B/bin/twinray
limit=$1 start=$(date +%s)
R=$OUT/r2
mkdir -p $R
step() { if [ $(( $(date +%s) - start )) -gt "$limit" ]; then echo "stopped before: $*"; return 1; fi; echo "== +$(( $(date +%s) - start ))s $*"; }
$T info > $R/info.txt 2>&1
nvidia-smi --query-gpu=timestamp,clocks.sm,clocks.mem,power.draw,temperature.gpu --format=csv -lms 200 > $R/clocks.csv 2>&1 &
SIZE="--width 1920 --height 1080"
for kind in monolithic libraries; do
  step places sphere 16 $kind && $T --pipeline $kind places sphere --spp 16 $SIZE --places 16 --moves none,code,reused --out $R/places-sphere16-$kind.json 2>&1 | grep -v WARN
done
step places swarm 16 monolithic && $T --pipeline monolithic places swarm --spp 16 $SIZE --places 12 --moves code,reused --out $R/places-swarm16-monolithic.json 2>&1 | grep -v WARN
BENCH="$SIZE --sets glsl,rust --null --runs 10 --warmup 2 --reference-spp 64 --shadow-spp none --probes none --images none --cache /tmp/refs"
step bench monolithic && $T --pipeline monolithic bench sphere swarm --spp 16 --placements 24 $BENCH --out $R/bench-mono 2>&1 | grep -v WARN | grep "/"
echo "== end +$(( $(date +%s) - start ))s"
kill %1 2>/dev/null
cd $OUT && tar czf r2.tgz r2 && rm -rf r2
