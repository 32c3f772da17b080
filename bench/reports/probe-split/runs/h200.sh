#!/bin/bash
# The probe's t error by source on the GPU machine (issue 26 item 6). Run from the repository
# root after `cargo xtask bundle --out .device/new`, with the bundle carried as `.device/`.
# Issue 26 item 6: the probe's t error split by source, on NVIDIA.
cd "$(dirname "$0")/.."
export LD_LIBRARY_PATH=$PWD/.device/new/lib
N=$PWD/.device/new/bin/twinray
o=$OUT/witness; mkdir -p $o
$N info > $o/info.txt 2>&1
for s in rust glsl; do
  $N probe probes/far-instances.toml --shaders $s > $o/far-instances-$s.txt 2>&1
  $N probe probes/far-instances.toml --shaders $s --json > $o/far-instances-$s.json 2>>$o/err.txt
  for f in robust naive; do $N probe probes/far-sphere.toml --shaders $s --formula $f > $o/far-sphere-$f-$s.txt 2>&1; done
  $N probe probes/cutout-holes.toml --shaders $s > $o/cutout-holes-$s.txt 2>&1
  $N probe probes/surface-rays.toml --shaders $s > $o/surface-rays-$s.txt 2>&1
done
$N stability --sets 'rust;glsl' --json > $o/stability.json 2>$o/stability.err
echo "stability rc $?" >> $o/err.txt
$N stability --sets 'rust;glsl' > $o/stability.txt 2>&1
tar czf $OUT/witness.tgz -C $OUT witness && rm -rf $o
