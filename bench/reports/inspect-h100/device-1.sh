#!/bin/sh
# twinray inspect on the H100: the driver's stack size per stage beside the bytes the
# analysis finds live across each call, both sets, ray generation specialised for 1 and 16
# spp. Then the between-run spread of Rust/GLSL (issue 40 item 4): swarm at 16 spp, three
# separate processes in each label order.
# Run from the bundle's parent (target/), with spirv-opt copied into twinray-bench/bin.
here=$(cd "$(dirname "$0")" && pwd)/twinray-bench
export LD_LIBRARY_PATH="$here/lib" PATH="$here/bin:$PATH"
T="$here/bin/twinray"
$T info | head -3
for spp in 1 16; do
  $T inspect --a rust --b glsl --spp $spp | tee "$OUT/side-$spp.txt"
done
for s in rust glsl; do
  $T inspect $s --json > "$OUT/$s.json"
  $T inspect $s --values > "$OUT/$s.txt"
done
COMMON="--width 1920 --height 1080 --spp 16 --runs 10 --warmup 3 --placements 6 --null --reference-spp 256 --shadow-spp none --probes none --images none --cache /tmp/refs"
for r in 1 2 3; do
  for order in glsl,rust rust,glsl; do
    echo "run $r $order $(date +%T)"
    $T bench swarm $COMMON --sets $order --out "$OUT/swarm-$order-$r" 2>&1 | grep -v WARN | tail -6
  done
done
