#!/bin/bash
# Issue 27: twinray explain on NVIDIA: rust against glsl on the pixels compare names and a grid,
# and the planted naive sphere.
cd "$(dirname "$0")/.."
export LD_LIBRARY_PATH=$PWD/.device/new/lib
N=$PWD/.device/new/bin/twinray
o=$OUT/explain; mkdir -p $o
$N info > $o/info.txt 2>&1
for s in showcase cutout meshes lights torus materials; do
  $N compare $s --a rust --b glsl --runs 1 --placements 1 --warmup 0 --out-dir /tmp/cmp-$s --json > $o/compare-$s.json 2>>$o/err.txt
  for p in 10,10 100,100 200,150 250,120 300,200 60,250 380,280 320,180; do
    $N explain $s --pixel $p --b glsl --json > $o/explain-$s-${p/,/_}.json 2>>$o/err.txt || echo "$s $p rc $?" >> $o/err.txt
  done
  python3 - "$o/compare-$s.json" > $o/lines-$s.txt <<'PY'
import json,sys
for p in json.load(open(sys.argv[1])).get("pixels",[]): print(p["x"], p["y"])
PY
  while read x y; do
    $N explain $s --pixel $x,$y --b glsl --json > $o/named-$s-${x}_${y}.json 2>>$o/err.txt || echo "$s $x,$y rc $?" >> $o/err.txt
  done < $o/lines-$s.txt
done
B="rust,sphere_intersection=$PWD/spirv/rust/sphere_naive_intersection.spv"
$N compare tests/bisect/far-sphere.toml --a rust --b "$B" --runs 1 --placements 1 --out-dir /tmp/cmp-far --json > $o/compare-far.json 2>>$o/err.txt
for p in 12,12 37,33 48,48; do
  $N explain tests/bisect/far-sphere.toml --pixel $p --b "$B" > $o/far-${p/,/_}.txt 2>>$o/err.txt
done
tar czf $OUT/explain.tgz -C $OUT explain && rm -rf $o
