#!/bin/sh
# Issue 40 item 5, lavapipe must not get slower: each set at HEAD against the same language's
# modules from da63c8e (before issue 40 changed any stage), with the null control (a salted
# copy of the old set), on every built-in scene at 1 and 16 spp, 480x270.
# Usage: sh run.sh OUT (from the repository root, after cargo build --release).
out=${1:-/tmp/issue40-lavapipe}
for s in rust glsl; do
  mkdir -p "/tmp/old/$s" && git archive da63c8e "spirv/$s" | tar x -C "/tmp/old/$s" --strip-components=2
  target/release/twinray bench --sets "/tmp/old/$s,$s" --null --spp 1,16 --width 480 --height 270 \
    --runs 10 --warmup 1 --placements 4 --reference-spp 64 --shadow-spp none --probes none \
    --images none --cache /tmp/refs --out "$out/$s" 2>&1 | grep -v WARN | grep " spp "
done
