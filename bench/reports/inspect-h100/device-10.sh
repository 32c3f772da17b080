#!/bin/sh
# Issue 40 item 5 (first pass): Rust against GLSL on every built-in scene at 1 and 16 spp,
# 1920x1080, each set alone in two processes per round (bench --processes 2, 4 placements
# each). The Rust set is the folder v192/rust (spirv/rust of ea54abe; the bundle's built-in
# Rust set is a variant not kept). Scenes in two halves: sh device.sh 1 | sh device.sh 2.
here=$(cd "$(dirname "$0")" && pwd)/twinray-bench
export LD_LIBRARY_PATH="$here/lib" PATH="$here/bin:$PATH"
T="$here/bin/twinray"
case $1 in
  1) SCENES="box cone cutout cylinder instances lights materials meshes";;
  *) SCENES="orbit plane showcase sphere spheres swarm torus";;
esac
COMMON="--width 1920 --height 1080 --runs 10 --warmup 3 --placements 4 --processes 2 --reference-spp 256 --shadow-spp none --probes none --images none --cache /tmp/refs"
echo "bench $(date +%T)"
$T bench $SCENES --spp 1,16 $COMMON --sets "glsl,$here/v192/rust" --out "$OUT/t$1" 2>&1 | grep -v WARN | grep "/" | grep -v wrote
echo "end $(date +%T)"
cd "$OUT" && tar czf all.tgz t$1/results.json t$1/ratios.csv && rm -rf t$1
