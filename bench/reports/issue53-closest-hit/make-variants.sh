#!/bin/sh
# Issue 53: the closest-hit modules this folder timed, rebuilt into target/v53ch from the
# modules of commit ee67772 (before the fix) and the GLSL sources in variants/. Needs
# spirv-opt, spirv-cross and glslangValidator (Debian: spirv-tools, spirv-cross, glslang-tools).
# The raygen variants A to C and the closest hit's R2 are patches in variants/ (`git apply`
# on ee67772, then `cargo xtask shaders --out /tmp/vX`); R1 is the commit that landed.
#   sh bench/reports/issue53-closest-hit/make-variants.sh   (from the repository root)
set -eu
V=bench/reports/issue53-closest-hit/variants
D=target/v53ch
mkdir -p $D
git show ee67772:spirv/rust/procedural_closest_hit.spv > $D/rust.spv
git show ee67772:spirv/glsl/procedural_closest_hit.spv > $D/glsl.spv
opt() { spirv-opt --target-env=vulkan1.2 "$@"; }
# P1: every function inlined; P2: spirv-opt -O; P3: GLSL's through -O.
opt --inline-entry-points-exhaustive --eliminate-dead-functions --eliminate-dead-code-aggressive \
  --merge-blocks $D/rust.spv -o $D/P1.spv
opt -O $D/rust.spv -o $D/P2.spv
opt -O $D/glsl.spv -o $D/P3.spv
# XR, XG: each decompiled by SPIRV-Cross and compiled again by glslang.
for s in rust glsl; do
  spirv-cross --vulkan-semantics --version 460 $D/$s.spv --output $D/x_$s.rchit
done
glslangValidator -V --target-env vulkan1.2 -S rchit $D/x_rust.rchit -o $D/XR.spv
glslangValidator -V --target-env vulkan1.2 -S rchit $D/x_glsl.rchit -o $D/XG.spv
# OR, OG: the scene's features (none: 0) frozen in, then optimised, so that only the code a
# scene without features runs is left.
for s in rust glsl; do
  opt --set-spec-const-default-value "3:0" --freeze-spec-const --fold-spec-const-op-composite \
    $D/$s.spv -o $D/f_$s.spv
  opt -O --inline-entry-points-exhaustive -O $D/f_$s.spv -o $D/O$(echo $s | cut -c1 | tr rg RG).spv
done
# The hand-edited steps between them (variants/*.rchit; README says what each changes).
for v in og G1 G2 G3 G4 or or1 or2; do
  glslangValidator -V --target-env vulkan1.2 -S rchit $V/$v.rchit -o $D/$v.spv
done
ls $D
