#!/bin/sh
# The sets SETS (bench's --sets: folders of modules under target/, built-in sets, mixes) on
# each scene, every set alone on ROUNDS fresh devices at 1920x1080 and SPP: how the reports of
# bench/reports/ time one set against another on the GPU machine. Run from the repository root
# with the bundle of `cargo xtask bundle` (target/twinray-bench.tar.gz); it leaves NAME.tgz
# (every results.json, log and info.txt) in $OUT.
#   sh bench/device-sets.sh NAME ROUNDS SPP SETS SCENE...
# SIZES (WxH, space-separated) times each scene at other sizes than 1920x1080, and FLAGS
# adds bench flags (`--null --first-placement 1000`).
set -u
[ -x /tmp/twinray-bench/bin/twinray ] || tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
T=$B/bin/twinray
name=$1 rounds=$2 spp=$3 sets=$4
shift 4
R=$OUT/$name
mkdir -p $R
$T info > $R/info.txt 2>&1
for scene in "$@"; do
  for wh in ${SIZES:-1920x1080}; do
    w=${wh%x*} h=${wh#*x} s=$(date +%s)
    out=$R/$(basename $scene)
    [ "$wh" = 1920x1080 ] || out=$out-$wh
    $T bench $scene --sets "$sets" ${FLAGS:-} --width $w --height $h \
      --spp $spp --runs 10 --warmup 2 --placements 1 --processes $rounds --alone-in devices \
      --reference-spp 16 --shadow-spp none --probes none --images none --cache /tmp/refs --out $out > $out.log 2>&1
    echo "== $scene $wh: exit $?, $(( $(date +%s) - s )) s"
    grep " / " $out.log | cut -c1-130
  done
done
cd $OUT && tar czf $name.tgz $(find $name -name results.json -o -name '*.txt' -o -name '*.log') && rm -rf $name
