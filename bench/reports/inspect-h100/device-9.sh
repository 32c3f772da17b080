#!/bin/sh
# Issue 40 item 2: the shadow-sample loop bottom-tested too (184 bytes across a shadow ray)
# against the ray generation rewrite without it (v192/rust) and GLSL; 16 spp, then 1 spp.
here=$(cd "$(dirname "$0")" && pwd)/twinray-bench
export LD_LIBRARY_PATH="$here/lib" PATH="$here/bin:$PATH"
T="$here/bin/twinray"
$T inspect --a rust --b glsl --spp 16 --stage raygen | tail -1
$T inspect --a "$here/v192/rust" --b glsl --spp 16 --stage raygen | tail -1
COMMON="--width 1920 --height 1080 --runs 10 --warmup 3 --placements 4 --processes 2 --reference-spp 256 --shadow-spp none --probes none --images none --cache /tmp/refs"
echo "bench $(date +%T)"
$T bench swarm sphere showcase cylinder cone meshes --spp 16 $COMMON --sets "glsl,rust,$here/v192/rust" --out "$OUT/s16" 2>&1 | grep -v WARN | grep "/" | grep -v wrote
echo "end $(date +%T)"
cd "$OUT" && tar czf all.tgz s16/results.json s16/ratios.csv && rm -rf s16
