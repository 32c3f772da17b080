#!/bin/sh
# The payload poison's cost, as landed (six words): each set against its ray generation stage
# built without the fill (nopoison/), both label orders, 12 placements; null controls.
here=$(cd "$(dirname "$0")" && pwd)
export LD_LIBRARY_PATH="$here/lib"
bin="$here/bin/twinray"
out=${OUT:-/tmp/out}
mkdir -p "$out"
"$bin" info > /dev/null 2>&1 || export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
common="--width 1920 --height 1080 --placements 12 --runs 10 --warmup 3 --json --out-dir /tmp/cmp"
n="$here/nopoison"
run() { name=$1; shift; "$bin" compare $scene "$@" $common > "$out/$scene-$name.json" 2>"$out/$scene-$name.err"; }
for scene in showcase lights swarm spheres; do
  for l in glsl rust; do
    run $l-poison-none --a $l --b "$l,raygen=$n/$l-raygen.spv"
    run $l-none-poison --a "$l,raygen=$n/$l-raygen.spv" --b $l
  done
done
scene=showcase; run glsl-null --a glsl --b glsl; run rust-null --a rust --b rust
cd "$out" && tar czf results3.tgz *.json *.err && rm -f *.json *.err
