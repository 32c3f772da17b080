#!/bin/sh
# The scene table (bench/reports/scene-table/README.md), twice in one go: run 1 (`glsl,rust`,
# places from 0), then run 2 (`rust,glsl`, places from 1000), every set alone on ROUNDS fresh
# devices per cell, with the null control. Run from the repository root on the GPU machine with
# the bundle of `cargo xtask bundle` (target/twinray-bench.tar.gz).
# Run N names the sets in run 1's order if N is odd, run 2's if even, and takes places from
# (N - 1) x 1000, so that no two runs share a place.
# Stops before a scene that would start past SECONDS; the same command again (on the same
# warm machine) goes on where it stopped: finished cells are marked in /tmp/t53-done, and the
# references are cached in /tmp/refs.
# RUNS (default "1 2") picks the runs, so that a run left unfinished can be completed alone, or
# a third run made (RUNS=3).
#   sh bench/reports/scene-table/device-runs.sh NAME SECONDS ROUNDS SCENE...
set -u
[ -x /tmp/twinray-bench/bin/twinray ] || tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
T=$B/bin/twinray
name=$1 limit=$2 rounds=$3
shift 3
start=$(date +%s)
R=$OUT/$name
mkdir -p $R /tmp/t53-done
$T info > $R/info.txt 2>&1
for run in ${RUNS:-1 2}; do
  if [ $((run % 2)) = 1 ]; then sets=glsl,rust; else sets=rust,glsl; fi
  first=$(( (run - 1) * 1000 ))
  for scene in "$@"; do
    base=$(basename $scene)
    [ -e /tmp/t53-done/$run-$base ] && continue
    if [ $(( $(date +%s) - start )) -gt "$limit" ]; then echo "stopped before run $run $scene"; break 2; fi
    s=$(date +%s)
    out=$R/run$run/$base
    mkdir -p $R/run$run
    $T bench $scene --sets $sets --null --width 1920 --height 1080 --spp 1,16 --runs 10 --warmup 2 \
      --placements 1 --processes $rounds --alone-in devices --first-placement $first \
      --reference-spp 64 --shadow-spp none --probes none --images none --cache /tmp/refs \
      --out $out > $out.log 2>&1
    echo "== run $run $scene: exit $?, $(( $(date +%s) - s )) s"
    grep "/" $out.log | grep -v 'WARN\|wrote'
    touch /tmp/t53-done/$run-$base
  done
done
echo "== end +$(( $(date +%s) - start ))s"
cd $OUT && tar czf $name.tgz $(find $name -name results.json -o -name '*.txt' -o -name '*.log') && rm -rf $name
