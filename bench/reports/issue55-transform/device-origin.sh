#!/bin/sh
# Issue 55 item 4 on the GPU machine, from the repository root with the bundle
# (`cargo xtask bundle`): the hard-case suite in both sets, then the far mesh probed at world
# coordinates (as probes/far-mesh.toml asks) and at the default local origin (the same file
# without its `gpu_origin` line), both sets.
#   sh bench/reports/issue55-transform/device-origin.sh NAME
set -u
[ -x /tmp/twinray-bench/bin/twinray ] || tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
name=$1
R=$OUT/$name
mkdir -p $R
$B/bin/twinray info > $R/info.txt 2>&1
s=$(date +%s)
$B/bin/twinray stability --json > $R/stability.json 2> $R/stability.err
echo "== stability: exit $?, $(( $(date +%s) - s )) s"
grep -v '^gpu_origin' probes/far-mesh.toml > /tmp/far-mesh-local.toml
for set in rust glsl; do
  $B/bin/twinray probe probes/far-mesh.toml --shaders $set > $R/far-mesh-world-$set.txt 2>&1
  echo "== far-mesh world $set: exit $?"
  $B/bin/twinray probe /tmp/far-mesh-local.toml --shaders $set > $R/far-mesh-local-$set.txt 2>&1
  echo "== far-mesh local $set: exit $?"
done
tail -n 4 $R/far-mesh-*.txt
