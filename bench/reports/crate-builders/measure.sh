#!/bin/sh
# Times the two ways of building a shader crate written by `twinray new`, on cold and warm
# caches: `twinray build` (twinray's own spirv-builder binary) and cargo-gpu 0.11.0.
# Usage: measure.sh TWINRAY CARGO_GPU WORK_DIR   (writes WORK_DIR/times.tsv)
# Cold: an empty XDG_CACHE_HOME for each (the pinned nightly already installed, crates in
# cargo's registry), so each compiles rust-gpu's backend, then the crate. Warm: the same
# crate again unchanged, then after a one-line edit of its closest hit.
set -eu
twinray=$1; gpu=$2; work=$3
mkdir -p "$work"; cd "$work"; rm -rf ours theirs cache-ours cache-theirs out; : > times.tsv
now() { date +%s.%N; }
edit() { sed -i 's/shading::material_color(m, p, n)$/shading::material_color(m, p, n) * 0.5/' "$1/src/lib.rs"; }
step() { # label, command...
  label=$1; shift; start=$(now); "$@" > "$label.log" 2>&1; end=$(now)
  printf '%s\t%.1f\n' "$label" "$(echo "$end - $start" | bc)" >> times.tsv
}
"$twinray" new ours > /dev/null; "$twinray" new theirs > /dev/null
export XDG_CACHE_HOME="$work/cache-ours"
step ours-cold "$twinray" build ours
step ours-unchanged "$twinray" build ours
edit ours; step ours-edit "$twinray" build ours
export XDG_CACHE_HOME="$work/cache-theirs"
set -- --shader-crate theirs --output-dir out --target spirv-unknown-vulkan1.1-spv1.4 --multimodule \
  --spirv-metadata none --capabilities RayTracingKHR --capabilities RayQueryKHR \
  --capabilities RuntimeDescriptorArray --extensions SPV_KHR_ray_tracing --extensions SPV_KHR_ray_query \
  --extensions SPV_EXT_descriptor_indexing --auto-install-rust-toolchain
step cargo-gpu-cold "$gpu" gpu build "$@"
step cargo-gpu-unchanged "$gpu" gpu build "$@"
edit theirs; step cargo-gpu-edit "$gpu" gpu build "$@"
du -sh cache-ours cache-theirs | sed 's/^/size\t/' >> times.tsv
cat times.tsv
