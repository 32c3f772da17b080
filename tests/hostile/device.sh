#!/bin/bash
# The deadline, device-lost and hostile-stage paths on a GPU machine (the H100 here), with
# the bundle of `cargo xtask bundle`, the library's unit-test binary copied into it as
# BUNDLE/unit-tests (`cargo test --release -p twinray-host --lib --no-run` prints its path), and
# the stages of tests/hostile/stages/ compiled by glslang into STAGES (long.rgen as
# long-N.spv for SPIN=N, N in 1 300 1000 3000 10000); SCENES is tests/reach:
#
#   bash tests/hostile/device.sh BUNDLE STAGES SCENES > report.txt
#
# A long loop that ends (not a runaway) is calibrated to about 20 s, then run under a 5 s
# deadline (exit 3 expected, and the GPU idle right after) and under a 60 s one (it finishes).
set -u
bundle=$1; stages=$2; scenes=$3
export LD_LIBRARY_PATH="$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
T="$bundle/bin/twinray"
small="--width 64 --height 48"
out=$(mktemp -d)
say() { echo "== $*"; }
ran() { # label, command...: exit code, seconds, the first line of stderr and the FAIL lines
    label=$1; shift
    start=$(date +%s.%N)
    "$@" > "$out/stdout" 2> "$out/stderr"; code=$?
    took=$(awk "BEGIN { printf \"%.1f\", $(date +%s.%N) - $start }")
    echo "$label: exit $code in ${took} s"
    head -c 600 "$out/stderr" | head -1
    grep -E "FAIL|not written|non-finite" "$out/stdout" | head -3
}
stamp() { # label, command...: when its stderr lines came and when it ended, from its start
    label=$1; shift; t0=$(date +%s.%N)
    "$@" 2>&1 >/dev/null | while IFS= read -r l; do echo "  +$(awk "BEGIN{printf \"%.2f\", $(date +%s.%N)-$t0}") s: ${l:0:160}"; done
    echo "$label: ended at +$(awk "BEGIN{printf \"%.2f\", $(date +%s.%N)-$t0}") s"
}
gpu() { nvidia-smi --query-gpu=utilization.gpu,memory.used --format=csv,noheader 2>/dev/null || echo "no nvidia-smi"; }

say device; "$T" info | grep -E "device|driver|robustness"
say "sentinel setup cost"
"$bundle/unit-tests" --ignored sentinel_setup_cost --nocapture 2>&1 | grep "sentinel setup"
say "calibration of the long loop (SPIN=1)"
one=$("$T" render sphere $small --shaders "glsl,raygen=$stages/long-1.spv" --out "$out/l.png" --json | sed 's/.*"gpu_ms":\([0-9.]*\).*/\1/')
echo "SPIN=1: $one ms"
best=1; for n in 300 1000 3000 10000; do
    if awk "BEGIN { exit !($one * $n < 30000) }"; then best=$n; fi
done
echo "chosen SPIN=$best: about $(awk "BEGIN { printf \"%.0f\", $one * $best / 1000 }") s"
say "deadline: the long loop under --gpu-timeout 5"
gpu
stamp "long loop, 5 s deadline" "$T" render sphere $small --shaders "glsl,raygen=$stages/long-$best.spv" --out "$out/l.png" --gpu-timeout 5
echo "GPU right after: $(gpu)"; sleep 2; echo "GPU 2 s after: $(gpu)"
ran "long loop, 60 s deadline" "$T" render sphere $small --shaders "glsl,raygen=$stages/long-$best.spv" --out "$out/l.png" --gpu-timeout 60
say "device lost: a wild device address"
stamp "wild address, 10 s deadline" "$T" render sphere $small --shaders "glsl,raygen=$stages/wild.rgen.spv" --out "$out/w.png" --gpu-timeout 10
ran "after it, a good render" "$T" render sphere $small --shaders glsl --out "$out/g.png"
say "hostile stages"
ran "raygen writes nothing" "$T" compare sphere $small --a glsl --b "glsl,raygen=$stages/noop.rgen.spv" --runs 1 --warmup 0 --out-dir "$out/c"
ran "raygen writes half" "$T" render sphere $small --shaders "glsl,raygen=$stages/half.rgen.spv" --out "$out/h.png"
ran "probe writes nothing" "$T" probe "$bundle/probes/stability/sphere-far-1e3.toml" --shaders "glsl,probe=$stages/noop.rgen.spv"
ran "any-hit loops" "$T" render cutout --width 32 --height 24 --shaders "glsl,cutout_any_hit=$stages/spin.rahit.spv" --out "$out/s.png" --gpu-timeout 3
for t in far nan inf; do
    ran "intersection reports t $t" "$T" compare sphere $small --a glsl --b "glsl,sphere_intersection=$stages/t-$t.rint.spv" --runs 1 --warmup 0 --out-dir "$out/c"
done
ran "intersection reads out of bounds" "$T" compare sphere $small --a glsl --b "glsl,sphere_intersection=$stages/oob.rint.spv" --runs 1 --warmup 0 --out-dir "$out/c"
ran "same, no robust access" "$T" --no-robust-access compare sphere $small --a glsl --b "glsl,sphere_intersection=$stages/oob.rint.spv" --runs 1 --warmup 0 --out-dir "$out/c"
ran "miss returns NaN" "$T" compare sphere $small --a glsl --b "glsl,miss=$stages/nan.rmiss.spv" --runs 1 --warmup 0 --out-dir "$out/c"
say "the rays' reach at 1920x1080: Rust against GLSL"
for s in "$scenes/far-5000.toml" "$scenes/far-1e6.toml" showcase; do
    "$T" compare "$s" --width 1920 --height 1080 --runs 10 --warmup 3 --out-dir "$out/c" | grep -E "^scene|ratio|rmse|hit mism|PASS|FAIL"
done
say "robust access: GPU ms of each set, robust on and off, alternating processes (1920x1080)"
for i in 1 2 3; do
    for flag in "" "--no-robust-access"; do
        line=$("$T" $flag compare showcase --width 1920 --height 1080 --runs 20 --warmup 3 --out-dir "$out/c" --json)
        a=$(echo "$line" | sed 's/.*"gpu_ms_a":\([0-9.]*\).*/\1/'); b=$(echo "$line" | sed 's/.*"gpu_ms_b":\([0-9.]*\).*/\1/')
        echo "round $i ${flag:-robust}: rust $a ms, glsl $b ms"
    done
done
