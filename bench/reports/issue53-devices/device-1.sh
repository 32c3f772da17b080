#!/bin/sh
# Issue 53 item 2, regimes: does a fresh Vulkan device in the bench's own process time a set
# as a fresh child process does? `bench --processes P --placements 4` times each set alone
# per round, each child starting at places of its own (Isolation::first_placement); with
# --alone-in devices each "child" is a new device in the parent instead. Same first
# placements in both, so each child's time can be set beside its device's.
#   sh bench/reports/issue53-devices/device-1.sh SECONDS PROCESSES SCENE...
set -u
tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
T=$B/bin/twinray
limit=$1 processes=$2
shift 2
start=$(date +%s)
R=$OUT/d1
mkdir -p $R
$T info > $R/info.txt 2>&1
BENCH="--width 1920 --height 1080 --spp 16 --runs 10 --warmup 2 --placements 4 --processes $processes --reference-spp 16 --shadow-spp none --probes none --images none --cache /tmp/refs"
for scene in "$@"; do
  for how in processes devices devices2 processes2; do
    if [ $(( $(date +%s) - start )) -gt "$limit" ]; then echo "stopped before $how $scene"; continue; fi
    echo "== +$(( $(date +%s) - start ))s $how $scene"
    on=processes; case $how in devices*) on=devices;; esac
    $T bench $scene --sets glsl,rust $BENCH --alone-in $on --out $R/$how-$scene 2>&1 | grep -v WARN | grep "/"
  done
done
echo "== end +$(( $(date +%s) - start ))s"
cd $OUT && tar czf d1.tgz $(find d1 -name results.json -o -name '*.txt') && rm -rf d1
