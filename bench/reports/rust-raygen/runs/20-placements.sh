#!/bin/bash
# Issue 26: issue 15's variants that mattered, re-timed over placements: the Rust ray
# generation with bottom-tested sample loops (r_dowhile) or one loop (r_single), the Rust
# intersection stages with the bounds-checked primitive read (the landed change's undo), and
# the Rust ray generation alone in the GLSL set.
cd "$(dirname "$0")/.."
export LD_LIBRARY_PATH=$PWD/.device/new/lib
N=$PWD/.device/new/bin/twinray; S=$PWD/.device/exp; D=$PWD/.device
C="--width 1920 --height 1080 --runs 10 --warmup 3 --placements 8 --json --out-dir /tmp/o"
o=$OUT/raygen; mkdir -p $o; t0=$(date +%s)
for scene in showcase-16 cylinder-16 cone-16 sphere-16; do
  $N compare $S/$scene.toml --a rust --b glsl $C > $o/$scene-rust-glsl.json 2>&1
  $N compare $S/$scene.toml --a rust,raygen=$D/raygen_r_dowhile.spv --b rust $C > $o/$scene-r_dowhile-rust.json 2>&1
  $N compare $S/$scene.toml --a rust,raygen=$D/raygen_r_single.spv --b rust $C > $o/$scene-r_single-rust.json 2>&1
  $N compare $S/$scene.toml --a rust,intersection=$D/checked --b rust $C > $o/$scene-checked-rust.json 2>&1
  $N compare $S/$scene.toml --a glsl,raygen=rust --b glsl $C > $o/$scene-glslraygenrust-glsl.json 2>&1
  echo "$scene at +$(( $(date +%s)-t0 )) s"
done
tar czf $OUT/raygen.tgz -C $OUT raygen && rm -rf $o
