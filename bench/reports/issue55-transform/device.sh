#!/bin/sh
# Issue 55 on the GPU machine, from the repository root with the bundle
# (`cargo xtask bundle`) and the previous commit's sets in target/o-glsl and target/o-rust:
# the hard-case suite in both sets (accuracy on totals, and what the driver's transform would
# have given), then the cost of the stages' own transform: the sets against their old selves,
# every set alone on ROUNDS fresh devices at 1920x1080 (bench/reports/issue53-branches/device-sets.sh).
#   sh bench/reports/issue55-transform/device.sh NAME ROUNDS SCENE...
set -u
[ -x /tmp/twinray-bench/bin/twinray ] || tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
name=$1 rounds=$2
shift 2
mkdir -p $OUT/$name
s=$(date +%s)
$B/bin/twinray stability --json > $OUT/$name/stability.json 2> $OUT/$name/stability.err
echo "== stability: exit $?, $(( $(date +%s) - s )) s"
$B/bin/twinray info > $OUT/$name/info.txt 2>&1
sets=glsl,rust,target/o-glsl,target/o-rust
S=bench/reports/issue53-branches/device-sets.sh
sh $S ${name}-16 $rounds 16 $sets "$@"
sh $S ${name}-1 $rounds 1 $sets "$@"
cd $OUT && tar czf $name.tgz $name && rm -rf $name
