#!/bin/sh
# Issue 40 item 4: spacers drawn from the timed sets (salted copies of each), then each set
# alone in processes of its own, alternating, three processes per set.
here=$(cd "$(dirname "$0")" && pwd)/twinray-bench
export LD_LIBRARY_PATH="$here/lib" PATH="$here/bin:$PATH"
T="$here/bin/twinray"
COMMON="--width 1920 --height 1080 --spp 16 --runs 10 --warmup 3 --reference-spp 256 --shadow-spp none --probes none --images none --cache /tmp/refs"
show() { python3 -c "
import json,sys,math
d=json.load(open('$OUT/x/results.json'))
for r in d['rows']:
  m=r['placements']['median_ms']
  print('   ', r['scene'], r['set'], round(math.exp(sum(math.log(x) for x in m)/len(m)),3), [round(x,2) for x in m])
"; }
run() { echo "$* $(date +%T)"; $T bench "$@" $COMMON --out "$OUT/x" 2>&1 | grep -v WARN | grep "/" | grep -v wrote; show; }
for order in glsl,rust rust,glsl; do
  run swarm sphere --sets $order --null --placements 12
  run swarm sphere --sets $order --placements 12
done
for r in 1 2 3; do
  run swarm sphere showcase cylinder --sets rust --placements 4
  run swarm sphere showcase cylinder --sets glsl --placements 4
done
