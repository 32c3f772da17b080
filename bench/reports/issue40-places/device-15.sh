#!/bin/sh
# Issue 40 item 4: why a process now and then times a set 1.4 to 4 times slower than the same
# set at the same place in another process. Times GLSL alone on showcase at 1 spp (2 ms
# traces), at the place of 4 spacers, in N processes with the default 200 ms of warm-up and
# N with 1000 ms (TWINRAY_MIN_WARM_MS), alternating, while nvidia-smi logs the SM clock
# every 50 ms. Usage: sh device-15.sh N
here=$(cd "$(dirname "$0")" && pwd)/twinray-bench
export LD_LIBRARY_PATH="$here/lib" PATH="$here/bin:$PATH"
T="$here/bin/twinray"
n=${1:-8}
mkdir -p "$OUT/x"
nvidia-smi --query-gpu=timestamp,clocks.sm,clocks.mem,pstate,power.draw,clocks_throttle_reasons.active --format=csv,noheader -lms 50 > "$OUT/x/clocks.csv" 2>&1 &
smi=$!
i=0
while [ $i -lt "$n" ]; do
  for warm in 200 1000; do
    echo "start $warm $i $(date +%H:%M:%S.%N)" >> "$OUT/x/log.txt"
    TWINRAY_MIN_WARM_MS=$warm $T bench ${SCENE:-showcase} --sets glsl --spp 1 --width 1920 --height 1080 --runs 10 --warmup 2 --placements 2 --first-placement 8 --reference-spp 1 --cache /tmp/refs --shadow-spp none --probes none --images none --out "$OUT/x/w$warm-$i" > /dev/null 2>&1
    ms=$(tr -d "\n " < "$OUT/x/w$warm-$i/results.json" | grep -o "\"median_ms\":\[[^]]*\]")
    echo "end $warm $i $(date +%H:%M:%S.%N) $ms" >> "$OUT/x/log.txt"
    echo "$warm $i $ms"
  done
  i=$((i+1))
done
kill $smi
cd "$OUT" && tar czf x.tgz x/log.txt x/clocks.csv $(find x -name results.json) && rm -rf x
