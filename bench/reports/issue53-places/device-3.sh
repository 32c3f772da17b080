#!/bin/sh
# Issue 53, third run: bench's rounds of places (unsalted spacers, 20 ms of warm-up a place)
# at 1920x1080, 1 and 16 spp, with the null control; then each scene again in the other label
# order at other places (--first-placement 1000). One bench per scene and run, so that a run
# cut short keeps what it finished.
#   sh bench/reports/issue53-places/device-3.sh SECONDS ROUNDS SCENE...
set -u
tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
T=$B/bin/twinray
limit=$1 rounds=$2
shift 2
start=$(date +%s)
R=$OUT/r3
mkdir -p $R
step() { if [ $(( $(date +%s) - start )) -gt "$limit" ]; then echo "stopped before: $*"; return 1; fi; echo "== +$(( $(date +%s) - start ))s $*"; }
$T info > $R/info.txt 2>&1
nvidia-smi --query-gpu=timestamp,clocks.sm,clocks.mem,power.draw,temperature.gpu --format=csv -lms 200 > $R/clocks.csv 2>&1 &
BENCH="--width 1920 --height 1080 --spp 1,16 --null --runs 10 --warmup 2 --placements $rounds --reference-spp 64 --shadow-spp none --probes none --images none --cache /tmp/refs"
for scene in "$@"; do
  step a $scene && $T bench $scene --sets glsl,rust $BENCH --out $R/a-$scene 2>&1 | grep -v WARN | grep "/"
done
for scene in "$@"; do
  step b $scene && $T bench $scene --sets rust,glsl --first-placement 1000 $BENCH --out $R/b-$scene 2>&1 | grep -v WARN | grep "/"
done
echo "== end +$(( $(date +%s) - start ))s"
kill %1 2>/dev/null
cd $OUT && tar czf r3.tgz $(find r3 -name results.json -o -name '*.txt' -o -name '*.csv' | grep -v results.csv) && rm -rf r3
