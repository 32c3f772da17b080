#!/bin/sh
# Issue 53: Rust variants of ray generation and the procedural closest hit against the
# built-in sets, at 1920x1080 and 16 spp, every set alone on ROUNDS fresh devices. The
# variants' modules are in spv/ (README.md says what each changes); each is the Rust set with
# those modules swapped in. Run from the repository root with the bundle in target/.
#   sh bench/reports/issue53-variants/device.sh NAME ROUNDS SCENE...
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
root=$(pwd)
cd bench/reports/issue53-variants
v() { # the Rust set with variant $1's modules in
  s=rust
  for f in spv/$1/*.spv; do s="$s,$(basename $f .spv)=$f"; done
  echo $s
}
sets="glsl,rust,$(v A),$(v B),$(v C),$(v D),$(v E)"
for scene in "$@"; do
  s=$(date +%s)
  out=$R/$(basename $scene)
  $T bench $scene --sets "$sets" --width 1920 --height 1080 \
    --spp 16 --runs 10 --warmup 2 --placements 1 --processes $rounds --alone-in devices \
    --reference-spp 16 --shadow-spp none --probes none --images none --cache /tmp/refs --out $out > $out.log 2>&1
  echo "== $scene: exit $?, $(( $(date +%s) - s )) s"
  grep "glsl / " $out.log | cut -c1-160
done
cd $OUT && tar czf $name.tgz $(find $name -name results.json -o -name '*.txt' -o -name '*.log') && rm -rf $name
