#!/bin/bash
# Issue 26, first look: where does a set's time move with its place in the command?
cd "$(dirname "$0")/.."
export LD_LIBRARY_PATH=$PWD/.device/new/lib
N=$PWD/.device/new/bin/twinray; O=$PWD/.device/old/twinray; S=$PWD/.device/exp
C="--width 1920 --height 1080 --runs 20 --warmup 3"
o=$OUT/exp1; mkdir -p $o
$N info > $o/info.txt 2>&1
nvidia-smi -q -d CLOCK,PERFORMANCE > $o/clocks-before.txt 2>&1
t0=$(date +%s)
for scene in sphere-16 cylinder-16; do
for pair in "rust glsl" "glsl rust" "glsl glsl" "rust rust"; do set -- $pair
  $O compare $S/$scene.toml --a $1 --b $2 $C --json --out-dir /tmp/o > $o/old-$scene-$1-$2.json 2>$o/old-$scene-$1-$2.err
  $N compare $S/$scene.toml --a $1 --b $2 $C --placements 8 --json --out-dir /tmp/o > $o/new-$scene-$1-$2.json 2>$o/new-$scene-$1-$2.err
done; echo "$scene done at +$(( $(date +%s)-t0 )) s"; done
for i in 1 2 3; do
  $N compare $S/cylinder-16.toml --a glsl --b glsl $C --placements 8 --json --out-dir /tmp/o > $o/proc$i-cylinder-glsl-glsl.json 2>&1
done
$N --pipeline monolithic --no-pipeline-cache compare $S/cylinder-16.toml --a glsl --b glsl $C --placements 8 --json --out-dir /tmp/o > $o/mono-cylinder-glsl-glsl.json 2>&1
echo "procs done at +$(( $(date +%s)-t0 )) s"
$N bench sphere cylinder --sets glsl,glsl,glsl,glsl,rust,rust --spp 16 --placements 8 $C --shadow-spp none --probes none --images none --reference-spp 16 --cache /tmp/c --out /tmp/b1 > $o/bench6.txt 2>&1
cp /tmp/b1/results.json $o/bench6.json
echo "bench done at +$(( $(date +%s)-t0 )) s"
nvidia-smi -q -d CLOCK,PERFORMANCE > $o/clocks-after.txt 2>&1
tar czf $OUT/exp1.tgz -C $OUT exp1 && rm -rf $o
