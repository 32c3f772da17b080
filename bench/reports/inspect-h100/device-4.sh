#!/bin/sh
# Issue 40 item 4: which process history makes Rust/GLSL move? swarm at 16 spp; absolute
# per-set medians for several set lists.
here=$(cd "$(dirname "$0")" && pwd)/twinray-bench
export LD_LIBRARY_PATH="$here/lib" PATH="$here/bin:$PATH"
T="$here/bin/twinray"
COMMON="--width 1920 --height 1080 --spp 16 --runs 10 --warmup 3 --reference-spp 256 --shadow-spp none --probes none --images none --cache /tmp/refs"
show() { python3 -c "
import json,sys
d=json.load(open('$OUT/x/results.json'))
print('   ', '; '.join('%s %.3f %s' % (r['set'], r['gpu_ms']['median'] if isinstance(r['gpu_ms'],dict) else r['gpu_ms'], [round(x,2) for x in r['placements']['median_ms']]) for r in d['rows']))
"; }
run() { echo "$* $(date +%T)"; $T bench swarm $COMMON "$@" --out "$OUT/x" 2>&1 | grep -v WARN | grep "/" | grep -v wrote | grep -v copy; show; }
run --sets glsl,rust,rust --placements 6
run --sets rust,glsl,glsl --placements 6
run --sets glsl,rust,glsl,rust --placements 4
run --sets rust,glsl,rust,glsl --placements 4
run --sets rust,glsl --null --placements 1
run --sets rust,glsl --null --placements 12
run --sets rust --placements 2
run --sets glsl --placements 2
rm -rf "$OUT/x"
