#!/bin/sh
# Issue 53 item 2, regimes: does ballast (TWINRAY_BALLAST: pipelines kept and released over a
# process, so that the code heap a place starts from drifts) make runs that start their rounds
# elsewhere agree? sphere and swarm at 16 spp, GLSL against Rust, ROUNDS rounds, first
# placements 0, 1000 and 2000, without ballast and with up to CAP ballast pipelines.
#   sh bench/reports/issue53-ballast/device-1.sh ROUNDS CAP
set -u
tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
T=$B/bin/twinray
rounds=$1 cap=$2
start=$(date +%s)
R=$OUT/b1
mkdir -p $R
$T info > $R/info.txt 2>&1
BENCH="--width 1920 --height 1080 --spp 16 --runs 10 --warmup 2 --placements $rounds --reference-spp 16 --shadow-spp none --probes none --images none --cache /tmp/refs"
for ballast in 0 $cap; do
  for first in 0 1000 2000; do
    for scene in sphere swarm; do
      echo "== +$(( $(date +%s) - start ))s ballast $ballast first $first $scene"
      TWINRAY_BALLAST=$ballast $T bench $scene --sets glsl,rust --first-placement $first $BENCH --out $R/$ballast-$first-$scene 2>&1 | grep -v WARN | grep "/"
    done
  done
done
echo "== end +$(( $(date +%s) - start ))s"
cd $OUT && tar czf b1.tgz $(find b1 -name results.json -o -name '*.txt') && rm -rf b1
