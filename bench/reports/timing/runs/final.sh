#!/bin/bash
# Issue 26: every built-in scene at 1920x1080, 1 and 16 spp, Rust against GLSL with its interval
# over placements, and the null control (a salted copy of Rust) per scene.
cd "$(dirname "$0")/.."
export LD_LIBRARY_PATH=$PWD/.device/new/lib
N=$PWD/.device/new/bin/twinray
r=$OUT/h100; mkdir -p $r; t0=$(date +%s)
$N info > $r/device.txt 2>&1
cmd="bench --width 1920 --height 1080 --runs 10 --warmup 3 --placements 6 --null --spp 1,16 --reference-spp 1024 --shadow-spp none --probes none --images none --cache /tmp/cache --out $r"
$N $cmd > $r/bench.txt 2>&1; echo "bench rc $? at +$(( $(date +%s)-t0 )) s"
echo "$cmd" | sed "s|$r|REPORT|g" > $r/command.txt
tar czf $OUT/h100.tgz -C $OUT h100 && rm -rf $r
