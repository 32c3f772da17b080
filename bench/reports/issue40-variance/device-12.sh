#!/bin/sh
# Issue 40 item 4: is the code the driver compiles the level that moves between sessions?
# 1. The same set compiled cold three times (no twinray pipeline cache, no NVIDIA disk
#    cache): does the pipeline cache blob the driver hands back differ?
# 2. Three cells whose estimates disagreed between the two sessions' passes, each set
#    alone in 6 processes: every process compiling cold ("cold"), against the default where
#    the first process compiles and the rest read twinray's pipeline cache ("warm").
# Usage: sh device-12.sh SECONDS (stops starting benches after SECONDS).
here=$(cd "$(dirname "$0")" && pwd)/twinray-bench
export LD_LIBRARY_PATH="$here/lib" PATH="$here/bin:$PATH"
T="$here/bin/twinray"
limit=$1
start=$(date +%s)
mkdir -p "$OUT/d12"
for s in glsl rust; do
  for i in 1 2 3; do
    __GL_SHADER_DISK_CACHE=0 $T --pipeline-cache /tmp/pc-$s-$i render spheres --shaders $s --width 64 --height 64 --out /tmp/r-$s-$i.png >/dev/null 2>&1
    for f in /tmp/pc-$s-$i/*; do echo "$s $i $(wc -c < "$f") $(md5sum < "$f")"; done
  done
  for i in 2 3; do
    echo "$s 1 vs $i: $(cmp -l /tmp/pc-$s-1/* /tmp/pc-$s-$i/* 2>/dev/null | wc -l) bytes differ"
  done
done > "$OUT/d12/compile.txt" 2>&1
cat "$OUT/d12/compile.txt"
COMMON="--width 1920 --height 1080 --runs 10 --warmup 2 --placements 2 --processes 6 --reference-spp 64 --shadow-spp none --probes none --images none --cache /tmp/refs --sets glsl,rust"
for mode in cold warm; do
  for cell in instances:1 spheres:16 cylinder:16; do
    [ $(( $(date +%s) - start )) -gt "$limit" ] && echo "stopped before $mode $cell" && continue
    scene=${cell%:*} spp=${cell#*:}
    echo "$mode $scene $spp $(date +%T)"
    if [ $mode = cold ]; then
      __GL_SHADER_DISK_CACHE=0 $T --no-pipeline-cache bench $scene $COMMON --spp $spp --out "$OUT/d12/$mode/$scene-$spp" 2>&1 | grep -v WARN | grep "/" | grep -v wrote
    else
      $T --pipeline-cache /tmp/pcw-$scene-$spp bench $scene $COMMON --spp $spp --out "$OUT/d12/$mode/$scene-$spp" 2>&1 | grep -v WARN | grep "/" | grep -v wrote
    fi
  done
done
echo "end $(date +%T)"
cd "$OUT" && tar czf d12.tgz d12/compile.txt $(find d12 -name results.json -o -name ratios.csv) && rm -rf d12
