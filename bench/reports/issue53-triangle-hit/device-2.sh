#!/bin/sh
# Issue 53 item 4: the two minimal triangle closest hits of docs/upstream/nvidia-pointer-struct
# (closure.spv: three index reads through a closure, whose environment rust-gpu builds as a
# struct of pointers; direct.spv: the same reads without it), each in meshes and instances,
# each render in a process of its own, with the validation layer's core checks.
set -u
tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
T=$B/bin/twinray
R=$OUT/h2
mkdir -p $R
$T info > $R/info.txt 2>&1
for m in closure direct; do
  for scene in meshes instances; do
    $T render $scene --shaders rust,triangle_closest_hit=docs/upstream/nvidia-pointer-struct/$m.spv --out /tmp/$m.png > $R/$m-$scene.txt 2>&1
    echo "$m $scene: exit $? $(grep -v WARN $R/$m-$scene.txt | grep -E 'error|crash|FAIL' | head -1 | cut -c1-160)" | tee -a $R/crash.txt
  done
done
cd $OUT && tar czf h2.tgz h2 && rm -rf h2
