#!/bin/sh
# Issue 53 item 5, before the table: where a device's time goes with `--alone-in devices`
# (the debug line of each device), and whether a device made right after another needs the
# full warm-up (MIN_WARM_MS, 1000 ms) or times the same after 100 ms (TWINRAY_MIN_WARM_MS),
# child by child at the same first placements; `rule` leaves the warm-up to the rule the
# bench now follows (placement::warm_floor: 20 ms when the GPU ended warmed traces at most
# 500 ms before).
#   WARMS="1000 100 1000b" sh bench/reports/issue53-table/device-warm.sh PROCESSES SCENE...
set -u
tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
T=$B/bin/twinray
processes=$1
shift
start=$(date +%s)
R=$OUT/w
mkdir -p $R
$T info > $R/info.txt 2>&1
BENCH="--width 1920 --height 1080 --runs 10 --warmup 2 --placements 1 --processes $processes --alone-in devices --reference-spp 16 --shadow-spp none --probes none --images none --cache /tmp/refs"
for scene in "$@"; do
  for warm in ${WARMS:-1000 100 1000b}; do
    echo "== +$(( $(date +%s) - start ))s warm $warm $scene"
    s=$(date +%s)
    if [ $warm = rule ]; then unset TWINRAY_MIN_WARM_MS; else export TWINRAY_MIN_WARM_MS=${warm%b}; fi
    RUST_LOG=twinray=debug $T bench $scene --sets glsl,rust --spp 1,16 $BENCH \
      --out $R/warm$warm-$(basename $scene) > $R/warm$warm-$(basename $scene).log 2>&1
    echo "   $(( $(date +%s) - s )) s"; grep -c 'alone on a device' $R/warm$warm-$(basename $scene).log
    grep "/" $R/warm$warm-$(basename $scene).log | grep -v 'WARN\|DEBUG\|INFO' | tail -4
  done
done
echo "== end +$(( $(date +%s) - start ))s"
cd $OUT && tar czf w.tgz w && rm -rf w
