#!/bin/sh
# Issue 77 on the GPU machine, from the repository root with the bundle (`cargo xtask bundle`)
# and the previous commit's sets in target/o-glsl and target/o-rust (their stages transform the
# ray where it starts): the hard-case suite in both sets, then what bringing the ray near the
# primitive costs, the sets against their old selves, every set alone on ROUNDS fresh devices
# at 1920x1080 and SPP, on scenes whose far-instances feature is on (scenes/: built-in scenes
# with it forced).
# SETS reorders the sets (the default: glsl,rust,target/o-glsl,target/o-rust); `stability` runs the
# suite with the previous sets as well.
#   sh bench/reports/issue77-near/device.sh NAME ROUNDS SPP [stability]
set -u
[ -x /tmp/twinray-bench/bin/twinray ] || tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
name=$1 rounds=$2 spp=$3
mkdir -p $OUT/$name
if [ "${4:-}" = stability ]; then
  s=$(date +%s)
  $B/bin/twinray stability --json > $OUT/$name/stability.json 2> $OUT/$name/stability.err
  echo "== stability: exit $?, $(( $(date +%s) - s )) s"
  $B/bin/twinray stability --sets "target/o-rust;target/o-glsl" --json > $OUT/$name/stability-old.json 2> $OUT/$name/stability-old.err
  echo "== stability, previous sets: exit $?, $(( $(date +%s) - s )) s"
fi
D=bench/reports/issue77-near/scenes
sh bench/reports/issue53-branches/device-sets.sh ${name}-$spp $rounds $spp ${SETS:-glsl,rust,target/o-glsl,target/o-rust} \
  $D/sphere-far.toml $D/cylinder-far.toml $D/torus-far.toml $D/showcase-far.toml instances
cd $OUT && tar czf $name.tgz $name && rm -rf $name
