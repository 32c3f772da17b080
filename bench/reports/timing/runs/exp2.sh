#!/bin/bash
# Issue 26, second look: is it where the pipeline's code lands (build order), the trace order,
# or the SBT's address?
cd "$(dirname "$0")/.."
export LD_LIBRARY_PATH=$PWD/.device/new/lib
X=$PWD/.device/expbin/twinray; S=$PWD/.device/exp
C="--width 1920 --height 1080 --runs 20 --warmup 3 --placements 8 --json --out-dir /tmp/o"
o=$OUT/exp2; mkdir -p $o; t0=$(date +%s)
for scene in cylinder-16 sphere-16; do
 for sets in "glsl glsl" "rust rust"; do set -- $sets
  k="$scene-$1-$2"
  $X compare $S/$scene.toml --a $1 --b $2 $C > $o/base-$k.json 2>&1
  EXP_TRACE_REVERSE=1 $X compare $S/$scene.toml --a $1 --b $2 $C > $o/trev-$k.json 2>&1
  EXP_SBT_PAD=1 $X compare $S/$scene.toml --a $1 --b $2 $C > $o/sbtpad-$k.json 2>&1
  for n in 1 2 3; do EXP_SPACER=$n $X compare $S/$scene.toml --a $1 --b $2 $C > $o/spacer$n-$k.json 2>&1; done
  EXP_KEEP=1 $X compare $S/$scene.toml --a $1 --b $2 $C --placements 16 > $o/keep-$k.json 2>&1
 done; echo "$scene at +$(( $(date +%s)-t0 )) s"
done
EXP_KEEP=1 $X bench cylinder sphere --sets glsl,glsl,glsl,glsl,rust,rust --spp 16 --placements 8 --width 1920 --height 1080 --runs 20 --warmup 3 --shadow-spp none --probes none --images none --reference-spp 16 --cache /tmp/c --out /tmp/b2 > $o/keep-bench6.txt 2>&1
cp /tmp/b2/results.json $o/keep-bench6.json
echo "bench at +$(( $(date +%s)-t0 )) s"
tar czf $OUT/exp2.tgz -C $OUT exp2 && rm -rf $o
