#!/bin/sh
# Issue 40 item 4: two sets against three, whole pipelines against linked, with and without
# the pipeline cache; swarm at 16 spp, both label orders.
here=$(cd "$(dirname "$0")" && pwd)/twinray-bench
export LD_LIBRARY_PATH="$here/lib" PATH="$here/bin:$PATH"
T="$here/bin/twinray"
COMMON="--width 1920 --height 1080 --spp 16 --runs 10 --warmup 3 --placements 6 --reference-spp 256 --shadow-spp none --probes none --images none --cache /tmp/refs"
for variant in "two:" "nocache:--null" "mono:--null" "both:--null"; do
  name=${variant%%:*}; flags=${variant#*:}
  for order in glsl,rust rust,glsl; do
    case $name in
      nocache) G="--no-pipeline-cache";;
      mono) G="--pipeline monolithic";;
      both) G="--pipeline monolithic --no-pipeline-cache";;
      *) G="";;
    esac
    echo "$name $order $(date +%T)"
    $T $G bench swarm $COMMON $flags --sets $order --out "$OUT/x" 2>&1 | grep -v WARN | grep "/" | grep -v wrote
  done
done
