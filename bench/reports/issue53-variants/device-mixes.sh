#!/bin/sh
# Issue 53: which stage carries Rust's time on a scene: the Rust set with one stage (or two)
# taken from GLSL, against both sets, at 1920x1080 and 16 spp, every set alone on ROUNDS
# fresh devices. Run from the repository root with the bundle in target/.
#   sh bench/reports/issue53-variants/device-mixes.sh NAME ROUNDS SCENE...
set -u
[ -x /tmp/twinray-bench/bin/twinray ] || tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
T=$B/bin/twinray
name=$1 rounds=$2
shift 2
R=$OUT/$name
mkdir -p $R
$T info > $R/info.txt 2>&1
sets="glsl,rust,rust,intersection=glsl,rust,raygen=glsl,rust,closest_hit=glsl,rust,miss=glsl"
sets="$sets,rust,raygen=glsl,closest_hit=glsl,glsl,intersection=rust"
for scene in "$@"; do
  s=$(date +%s)
  out=$R/$(basename $scene)
  $T bench $scene --sets "$sets" --width 1920 --height 1080 \
    --spp 16 --runs 10 --warmup 2 --placements 1 --processes $rounds --alone-in devices \
    --reference-spp 16 --shadow-spp none --probes none --images none --cache /tmp/refs --out $out > $out.log 2>&1
  echo "== $scene: exit $?, $(( $(date +%s) - s )) s"
  grep "glsl / " $out.log | cut -c1-130
done
cd $OUT && tar czf $name.tgz $(find $name -name results.json -o -name '*.txt' -o -name '*.log') && rm -rf $name
