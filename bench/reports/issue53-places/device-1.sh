#!/bin/sh
# Issue 53, first H100 run: what a place changes (`twinray places`), and bench's rounds of
# places in one process against its --processes, on the same machine. Run from the
# repository root with the bundle (`cargo xtask bundle`) carried as target/twinray-bench.tar.gz:
#   sh bench/reports/issue53-places/device-1.sh SECONDS   (starts no step after SECONDS)
set -u
tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
T=$B/bin/twinray
limit=$1 start=$(date +%s)
R=$OUT/r1
mkdir -p $R
step() { if [ $(( $(date +%s) - start )) -gt "$limit" ]; then echo "stopped before: $*"; return 1; fi; echo "== +$(( $(date +%s) - start ))s $*"; }
$T info > $R/info.txt 2>&1
nvidia-smi --query-gpu=timestamp,clocks.sm,clocks.mem,power.draw,temperature.gpu --format=csv -lms 200 > $R/clocks.csv 2>&1 &
SIZE="--width 1920 --height 1080"
step places sphere 16 && $T places sphere --spp 16 $SIZE --places 16 --out $R/places-sphere16.json 2>&1 | grep -v WARN
step places swarm 16 && $T places swarm --spp 16 $SIZE --places 12 --out $R/places-swarm16.json 2>&1 | grep -v WARN
BENCH="$SIZE --sets glsl,rust --null --runs 10 --warmup 2 --reference-spp 64 --shadow-spp none --probes none --images none --cache /tmp/refs"
step bench in-process && $T bench sphere swarm cone --spp 1,16 --placements 24 $BENCH --out $R/bench 2>&1 | grep -v WARN | grep "/"
step bench processes && $T bench sphere --spp 16 --placements 2 --processes 6 $BENCH --out $R/bench-proc 2>&1 | grep -v WARN | grep "/"
echo "== end +$(( $(date +%s) - start ))s"
kill %1 2>/dev/null
cd $OUT && tar czf r1.tgz r1 && rm -rf r1
