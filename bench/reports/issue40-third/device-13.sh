#!/bin/sh
# Issue 40 item 4: each round's processes start at a later placement (bench --processes now
# passes --first-placement), so the rounds time the sets at 0, 1, 2 and 3 spacers. Three cells
# whose estimate moved between session 1 (4 placements: 0 and 1 spacers) and sessions 2 and 3
# (2 placements: 0 spacers only), each benched twice in separate runs.
# Usage: sh device-13.sh SECONDS (stops starting benches after SECONDS).
here=$(cd "$(dirname "$0")" && pwd)/twinray-bench
export LD_LIBRARY_PATH="$here/lib" PATH="$here/bin:$PATH"
T="$here/bin/twinray"
limit=$1
start=$(date +%s)
COMMON="--width 1920 --height 1080 --runs 10 --warmup 2 --placements 2 --processes 4 --reference-spp 64 --shadow-spp none --probes none --images none --cache /tmp/refs --sets glsl,$here/v40/old/rust"
for pass in 1 2; do
  for cell in spheres:16 instances:1 cylinder:16; do
    [ $(( $(date +%s) - start )) -gt "$limit" ] && echo "stopped before $pass $cell" && continue
    scene=${cell%:*} spp=${cell#*:}
    echo "pass $pass $scene $spp $(date +%T)"
    $T bench $scene $COMMON --spp $spp --out "$OUT/d13/p$pass/$scene-$spp" 2>&1 | grep -v WARN | grep "/" | grep -v wrote
  done
done
echo "end $(date +%T)"
cd "$OUT" && tar czf d13.tgz $(find d13 -name results.json -o -name ratios.csv) && rm -rf d13
