#!/bin/sh
# Issue 53 item 3, second run: each set specialised on the scene's features (built-in `rust`, `glsl`)
# against the same set built without texture code (`cargo xtask shaders --without textures
# --out target/without-textures`) and against the modules of e7ee105, which had no feature
# constant (target/old-sets, from `git show e7ee105:spirv/...`), at 1920x1080, 1 and 16 spp,
# every set at places of its own in one process. Unlike run 1: the other label order, rounds
# that start at place 1000, no e7ee105 sets, and the compares' lines kept in compare.txt.
#   sh bench/reports/issue53-features/device-1.sh SECONDS ROUNDS SCENE...
set -u
tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
T=$B/bin/twinray
limit=$1 rounds=$2
shift 2
start=$(date +%s)
R=$OUT/f2
mkdir -p $R
step() { if [ $(( $(date +%s) - start )) -gt "$limit" ]; then echo "stopped before: $*"; return 1; fi; echo "== +$(( $(date +%s) - start ))s $*"; }
$T info > $R/info.txt 2>&1
W=target/without-textures O=target/old-sets
SETS=glsl,$W/glsl,rust,$W/rust
BENCH="--width 1920 --height 1080 --spp 1,16 --runs 10 --warmup 2 --placements $rounds --first-placement 1000 --reference-spp 64 --shadow-spp none --probes none --images none --cache /tmp/refs"
# Correctness on NVIDIA first: scenes that use each feature, Rust against GLSL.
for scene in cutout lights materials showcase target/models/box-textured.gltf; do
  echo "== compare $scene"; $T compare $scene --a rust --b glsl 2>&1 | grep -E "PASS|FAIL|rmse|error" | head -3
done | tee $R/compare.txt
for scene in "$@"; do
  step $scene && $T bench $scene --sets $SETS $BENCH --out $R/$scene 2>&1 | grep -v WARN | grep "/"
done
echo "== end +$(( $(date +%s) - start ))s"
cd $OUT && tar czf f2.tgz $(find f2 -name results.json -o -name '*.txt') && rm -rf f2
