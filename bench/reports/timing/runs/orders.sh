#!/bin/bash
# Issue 26: identical sets in any order and number (2 to 6), and both label orders.
cd "$(dirname "$0")/.."
export LD_LIBRARY_PATH=$PWD/.device/new/lib
N=$PWD/.device/new/bin/twinray; S=$PWD/.device/exp
o=$OUT/orders; mkdir -p $o; t0=$(date +%s)
B="--spp 16 --placements 6 --width 1920 --height 1080 --runs 10 --warmup 3 --shadow-spp none --probes none --images none --reference-spp 16 --cache /tmp/c"
for sets in glsl,glsl glsl,glsl,glsl rust,glsl,glsl,rust,glsl,glsl; do
  $N bench cylinder sphere --sets $sets $B --out /tmp/b-$sets > $o/bench-$sets.txt 2>&1; cp /tmp/b-$sets/results.json $o/bench-$sets.json
  echo "$sets at +$(( $(date +%s)-t0 )) s"
done
C="--width 1920 --height 1080 --runs 10 --warmup 3 --placements 6 --json --out-dir /tmp/o"
for scene in cylinder-16 sphere-16; do for pair in "rust glsl" "glsl rust"; do set -- $pair
  $N compare $S/$scene.toml --a $1 --b $2 $C > $o/compare-$scene-$1-$2.json 2>&1
done; done
echo "compares at +$(( $(date +%s)-t0 )) s"
tar czf $OUT/orders.tgz -C $OUT orders && rm -rf $o
