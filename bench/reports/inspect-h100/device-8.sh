#!/bin/sh
# Issue 40 item 2: the Rust ray generation stage with its hit-id buffer checked before the
# loops, the ids written in the loop, bottom-tested sample loops and the light read by
# reference; against GLSL and against the Rust modules of before (old/rust: spirv/rust of
# 797661c). Stacks, then each set alone in two processes of its own per round.
here=$(cd "$(dirname "$0")" && pwd)/twinray-bench
export LD_LIBRARY_PATH="$here/lib" PATH="$here/bin:$PATH"
T="$here/bin/twinray"
$T inspect --a rust --b glsl --spp 16 | tail -7
$T inspect --a "$here/old/rust" --b rust --spp 16 --stage raygen | tail -2
$T inspect --a rust --b glsl --spp 1 --stage raygen | tail -1
COMMON="--width 1920 --height 1080 --runs 10 --warmup 3 --placements 4 --processes 2 --reference-spp 256 --shadow-spp none --probes none --images none --cache /tmp/refs"
echo "bench $(date +%T)"
$T bench swarm sphere showcase cylinder cone meshes --spp 16 $COMMON --sets "glsl,rust,$here/old/rust" --out "$OUT/new" 2>&1 | grep -v WARN | grep "/" | grep -v wrote
echo "end $(date +%T)"
cd "$OUT" && python3 -c "
import json
d=json.load(open('new/results.json'))
for r in d['rows']: print(r['scene'], r['set'][-12:], 'rmse', r['rmse'], 'mismatch', r['hit_mismatches'], 'stack', r['raygen_stack_bytes'])
" && tar czf all.tgz new/results.json new/ratios.csv && rm -rf new
