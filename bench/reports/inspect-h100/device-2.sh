#!/bin/sh
# Issue 40 item 4: with the Williams design of placement orders, does the label order still
# decide Rust/GLSL? Four scenes at 16 spp, 1920x1080, --null (three sets), 6 placements; two
# processes per label order. Then the stack sizes again.
here=$(cd "$(dirname "$0")" && pwd)/twinray-bench
export LD_LIBRARY_PATH="$here/lib" PATH="$here/bin:$PATH"
T="$here/bin/twinray"
$T info | head -2
$T inspect --a rust --b glsl --spp 16
COMMON="--width 1920 --height 1080 --spp 16 --runs 10 --warmup 3 --placements 6 --null --reference-spp 256 --shadow-spp none --probes none --images none --cache /tmp/refs"
for r in 1 2; do
  for order in glsl,rust rust,glsl; do
    echo "run $r $order $(date +%T)"
    $T bench swarm showcase sphere cylinder $COMMON --sets $order --out "$OUT/b-$r-${order%,*}" 2>&1 | grep -v WARN | grep "/"
  done
done
