#!/bin/sh
# Issue 53: the cylinder intersection keeping its nearest hit as plain values (variant F,
# patches/F.patch) against the Rust and GLSL sets, at 1920x1080, alone on ROUNDS devices.
#   sh bench/reports/issue53-variants/device-f.sh NAME ROUNDS SPP SCENE...
set -u
[ -x /tmp/twinray-bench/bin/twinray ] || tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
T=$B/bin/twinray
name=$1 rounds=$2 spp=$3
shift 3
R=$OUT/$name
mkdir -p $R
cd bench/reports/issue53-variants
f=cylinder_intersection=spv/F/cylinder_intersection.spv
for scene in "$@"; do
  out=$R/$(basename $scene)
  $T bench $scene --sets "glsl,rust,rust,$f,glsl,$f" --width 1920 --height 1080 \
    --spp $spp --runs 10 --warmup 2 --placements 1 --processes $rounds --alone-in devices \
    --reference-spp 16 --shadow-spp none --probes none --images none --cache /tmp/refs --out $out > $out.log 2>&1
  echo "== $scene: exit $?"
  grep " / " $out.log | cut -c1-150
done
cd $OUT && tar czf $name.tgz $(find $name -name results.json -o -name '*.log') && rm -rf $name
