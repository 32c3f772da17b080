#!/bin/sh
# Both committed sets, every module through `spirv-opt -O`, into target/opt-sets/{rust,glsl}.
set -eu
for s in rust glsl; do
  mkdir -p target/opt-sets/$s
  for f in spirv/$s/*.spv; do
    spirv-opt -O --target-env=vulkan1.1spv1.4 "$f" -o target/opt-sets/$s/$(basename "$f")
  done
done
