#!/bin/sh
# Issue 40 item 4: bench --processes 3 (each set alone in three processes of its own, rounds
# alternating the order), both label orders, --null; four scenes at 16 spp, 1920x1080.
here=$(cd "$(dirname "$0")" && pwd)/twinray-bench
export LD_LIBRARY_PATH="$here/lib" PATH="$here/bin:$PATH"
T="$here/bin/twinray"
COMMON="--width 1920 --height 1080 --spp 16 --runs 10 --warmup 3 --placements 4 --processes 3 --null --reference-spp 256 --shadow-spp none --probes none --images none --cache /tmp/refs"
for order in glsl,rust rust,glsl; do
  echo "$order $(date +%T)"
  $T bench swarm sphere showcase cylinder $COMMON --sets $order --out "$OUT/p-${order%,*}" 2>&1 | grep -v WARN | grep "/" | grep -v wrote
done
echo "end $(date +%T)"
cd "$OUT" && tar czf all.tgz p-*/results.json p-*/ratios.csv && rm -rf p-*
