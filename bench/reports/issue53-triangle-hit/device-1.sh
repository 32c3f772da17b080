#!/bin/sh
# Issue 53 item 4: does NVIDIA's driver still crash on a Rust triangle closest hit without
# bounds checks? Variants of shaders-rs/shaders/src/hit.rs, each built with
# `cargo xtask shaders --out target/v-X` (see README.md): U all eight reads unchecked (no
# closure), M only the object and material reads, V only the index and vertex reads, C all
# through a closure (the form that crashed in issue 40). Each renders meshes and instances in
# a process of its own (exit code kept); then the variants that made pipelines are timed.
#   sh bench/reports/issue53-triangle-hit/device-1.sh SECONDS ROUNDS
set -u
tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
T=$B/bin/twinray
limit=$1 rounds=$2
start=$(date +%s)
R=$OUT/h1
mkdir -p $R
$T info > $R/info.txt 2>&1
ok=""
for v in U M V C; do
  fine=yes
  for scene in meshes instances target/models/box-textured.gltf; do
    $T compare $scene --a glsl --b rust,closest_hit=target/v-$v/rust --width 1920 --height 1080 > $R/compare-$v-$(basename $scene .gltf).txt 2>&1
    rc=$?
    echo "variant $v $scene: exit $rc $(grep -E 'PASS|FAIL' $R/compare-$v-$(basename $scene .gltf).txt | head -1)" | tee -a $R/crash.txt
    [ $rc -gt 1 ] && fine=no
  done
  [ $fine = yes ] && ok="$ok,rust,closest_hit=target/v-$v/rust"
done
echo "== +$(( $(date +%s) - start ))s timing glsl,rust$ok"
BENCH="--width 1920 --height 1080 --spp 1,16 --runs 10 --warmup 2 --placements $rounds --reference-spp 64 --shadow-spp none --probes none --images none --cache /tmp/refs"
for scene in meshes target/models/box-textured.gltf instances; do
  if [ $(( $(date +%s) - start )) -gt "$limit" ]; then echo "stopped before $scene"; break; fi
  $T bench $scene --sets glsl,rust$ok $BENCH --out $R/$(basename $scene .gltf) 2>&1 | grep -v WARN | grep "/"
done
echo "== end +$(( $(date +%s) - start ))s"
cd $OUT && tar czf h1.tgz $(find h1 -name results.json -o -name '*.txt') && rm -rf h1
