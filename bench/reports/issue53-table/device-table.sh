#!/bin/sh
# Issue 53 item 5: the Rust/GLSL table at 1920x1080, 1 and 16 spp, every set (and the null
# control's copy of the first) timed alone on ROUNDS fresh Vulkan devices of one placement
# each, per scene; the ratio's interval over the rounds. Stops before a scene that would start
# past SECONDS; a later call goes on with the scenes left.
#   sh bench/reports/issue53-table/device-table.sh NAME SETS FIRST SECONDS ROUNDS SCENE...
# NAME names the results folder; SETS is glsl,rust (run 1) or rust,glsl (run 2, the other
# label order); FIRST is --first-placement (run 2 times places run 1 did not).
set -u
tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
T=$B/bin/twinray
name=$1 sets=$2 first=$3 limit=$4 rounds=$5
shift 5
start=$(date +%s)
R=$OUT/$name
mkdir -p $R
$T info > $R/info.txt 2>&1
BENCH="--width 1920 --height 1080 --spp 1,16 --runs 10 --warmup 2 --placements 1 --processes $rounds --alone-in devices --first-placement $first --reference-spp 64 --shadow-spp none --probes none --images none --cache /tmp/refs"
for scene in "$@"; do
  if [ $(( $(date +%s) - start )) -gt "$limit" ]; then echo "stopped before $scene"; continue; fi
  s=$(date +%s)
  out=$R/$(basename $scene)
  $T bench $scene --sets $sets --null $BENCH --out $out > $out.log 2>&1
  echo "== $scene: exit $?, $(( $(date +%s) - s )) s"
  grep "/" $out.log | grep -v 'WARN\|wrote'
done
echo "== end +$(( $(date +%s) - start ))s"
cd $OUT && tar czf $name.tgz $(find $name -name results.json -o -name '*.txt' -o -name '*.log') && rm -rf $name
