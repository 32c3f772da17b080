#!/bin/bash
# Issue 26 targets: for every cell of the H100 table, what the Rust set's remaining cost is.
# One bench per samples-per-pixel count: rust, glsl, GLSL with the Rust ray generation
# (`glsl,raygen=rust`), and Rust with the bottom-tested sample loops (`r_dowhile`, issue 15).
# Usage: attribution.sh SPP
cd "$(dirname "$0")/.."
export LD_LIBRARY_PATH=$PWD/.device/new/lib
N=$PWD/.device/new/bin/twinray
spp=$1; r=$OUT/attribution-$spp; mkdir -p $r; t0=$(date +%s)
$N info > $r/device.txt 2>&1
sets="rust,glsl,glsl,raygen=rust,rust,raygen=$PWD/.device/raygen_r_dowhile.spv"
cmd="bench --sets $sets --width 1920 --height 1080 --runs 10 --warmup 3 --placements 6 --spp $spp --reference-spp 1024 --shadow-spp none --probes none --images none --cache /tmp/cache --out $r"
$N $cmd > $r/bench.txt 2>&1; echo "bench rc $? at +$(( $(date +%s)-t0 )) s"
echo "$cmd" | sed "s|$r|REPORT|g; s|$PWD/||g" > $r/command.txt
rm -rf $r/images $r/plots $r/index.html
tar czf $OUT/attribution-$spp.tgz -C $OUT attribution-$spp && rm -rf $r
