#!/bin/sh
# Issue 40 item 5: GLSL against Rust (and the null control, a salted GLSL copy) at 1 and 16
# spp, 1920x1080, each set alone in three processes per round (bench --processes 3,
# 2 placements each). One bench per scene, so that a run cut short keeps the scenes it
# finished. Usage: sh device-11.sh TAG SECONDS SETS SCENE... (stops starting scenes after
# SECONDS). A set written @NAME is the folder NAME in the bundle. SPP, NULL and PROCESSES
# (default 1,16, --null and 3) change what each bench times.
here=$(cd "$(dirname "$0")" && pwd)/twinray-bench
export LD_LIBRARY_PATH="$here/lib" PATH="$here/bin:$PATH"
T="$here/bin/twinray"
tag=$1 limit=$2 sets=$3
shift 3
COMMON="--width 1920 --height 1080 --spp ${SPP:-1,16} ${NULL---null} --runs 10 --warmup 2 --placements 2 --processes ${PROCESSES:-3} --reference-spp 64 --shadow-spp none --probes none --images none --cache /tmp/refs"
start=$(date +%s)
for scene in "$@"; do
  [ $(( $(date +%s) - start )) -gt "$limit" ] && echo "stopped before $scene" && break
  echo "$scene $(date +%T) +$(( $(date +%s) - start ))s"
  $T bench "$scene" $COMMON --sets "$(echo "$sets" | sed "s#@#$here/#g")" --out "$OUT/$tag/$scene" 2>&1 | grep -v WARN | grep "/" | grep -v wrote
done
echo "end $(date +%T)"
cd "$OUT" && tar czf "$tag.tgz" $(find "$tag" -name results.json -o -name ratios.csv) && rm -rf "$tag"
