#!/bin/sh
# Issue 53, fourth run: why two in-process benches of one cell disagree. The same command
# again (is a run deterministic?), other places in the same label order, the other label
# order at the same places, and each set alone in processes of its own (8 per set, 6 places
# each), on sphere and then swarm at 16 spp.
#   sh bench/reports/issue53-places/device-4.sh SECONDS
set -u
tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
T=$B/bin/twinray
limit=$1 start=$(date +%s)
R=$OUT/r4
mkdir -p $R
step() { if [ $(( $(date +%s) - start )) -gt "$limit" ]; then echo "stopped before: $*"; return 1; fi; echo "== +$(( $(date +%s) - start ))s $*"; }
$T info > $R/info.txt 2>&1
BENCH="--width 1920 --height 1080 --spp 16 --null --runs 10 --warmup 2 --reference-spp 64 --shadow-spp none --probes none --images none --cache /tmp/refs"
for scene in sphere swarm; do
  step same $scene && $T bench $scene --sets glsl,rust --placements 60 $BENCH --out $R/same-$scene 2>&1 | grep -v WARN | grep "/"
  step other-places $scene && $T bench $scene --sets glsl,rust --placements 60 --first-placement 2000 $BENCH --out $R/places-$scene 2>&1 | grep -v WARN | grep "/"
  step other-order $scene && $T bench $scene --sets rust,glsl --placements 60 $BENCH --out $R/order-$scene 2>&1 | grep -v WARN | grep "/"
  step processes $scene && $T bench $scene --sets glsl,rust --placements 6 --processes 8 $BENCH --out $R/proc-$scene 2>&1 | grep -v WARN | grep "/"
done
echo "== end +$(( $(date +%s) - start ))s"
cd $OUT && tar czf r4.tgz $(find r4 -name results.json -o -name '*.txt') && rm -rf r4
