#!/bin/bash
# Issue 26, the new instrument: each set of a placement built, timed and released in turn.
cd "$(dirname "$0")/.."
export LD_LIBRARY_PATH=$PWD/.device/new/lib
N=$PWD/.device/new/bin/twinray; S=$PWD/.device/exp
C="--width 1920 --height 1080 --runs 20 --warmup 3 --placements 8 --json --out-dir /tmp/o"
o=$OUT/exp3; mkdir -p $o; t0=$(date +%s)
for scene in cylinder-16 sphere-16; do
 for pair in "glsl glsl" "rust rust" "rust glsl" "glsl rust"; do set -- $pair
  $N compare $S/$scene.toml --a $1 --b $2 $C > $o/new-$scene-$1-$2.json 2>&1
 done; echo "$scene at +$(( $(date +%s)-t0 )) s"
done
$N bench cylinder sphere --sets glsl,glsl,glsl,glsl,rust,rust --spp 16 --placements 8 --width 1920 --height 1080 --runs 20 --warmup 3 --shadow-spp none --probes none --images none --reference-spp 16 --cache /tmp/c --out /tmp/b3 > $o/bench6.txt 2>&1
cp /tmp/b3/results.json $o/bench6.json
echo "bench at +$(( $(date +%s)-t0 )) s"
tar czf $OUT/exp3.tgz -C $OUT exp3 && rm -rf $o
