#!/bin/sh
# On the GPU machine: (1) the peak host memory `render` reports (and `/usr/bin/time -v`) for a
# 2,000,000-triangle primitive (`bench/deforming.py still 1001`) against a 200-triangle one,
# three renders each, and ten million triangles (`still 2238`) once, now that `render` gives
# the scene's meshes up once uploaded; (2) both sets compared on every frame of glTF models
# placed by scene files: AnimatedMorphCube by an object and a grid of two, the same moved by
# the scene's [animation] as well, and simple_skin with AnimatedMorphCube (two animated models
# playing together), at 8 frames a second;
# (3) the KHR_mesh_quantization fuzz seed compared. Run from the repository root with
# target/dev/clip.tar.gz (`cargo xtask bundle --out target/dev/clip`) and target/dev/models
# (assimp's AnimatedMorphCube.gltf/.bin and simple_skin.gltf) carried; results under $OUT.
#   sh bench/reports/models/placed-runs.sh
set -u
[ -x /tmp/clip/bin/twinray ] || tar xzf target/dev/clip.tar.gz -C /tmp
export LD_LIBRARY_PATH=/tmp/clip/lib
T=/tmp/clip/bin/twinray
R=$OUT/placed
mkdir -p /tmp/sheets /tmp/placed $R
$T info > $R/info.txt 2>&1
python3 bench/deforming.py still 1001 /tmp/sheets/still-1001
python3 bench/deforming.py still 11 /tmp/sheets/still-11
for k in 1 2 3; do
  for n in 1001 11; do
    TWINRAY_MAX_MESH_BYTES=100000000 /usr/bin/time -v $T render /tmp/sheets/still-$n.gltf --width 1920 \
      --height 1080 --out /tmp/still.png > $R/still-$n-$k.log 2>&1
    echo "== still-$n ($k): exit $?"; grep -E "loaded|at its peak|Maximum resident" $R/still-$n-$k.log
  done
done
cp target/dev/models/AnimatedMorphCube.gltf target/dev/models/AnimatedMorphCube.bin \
  target/dev/models/simple_skin.gltf /tmp/placed/
head='[image]
width = 1920
height = 1080
[camera]
eye = [0.0, 0.0, 9.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 1.0, 0.0]
fov_y_degrees = 50.0
[[lights]]
kind = "directional"
direction = [0.2, 0.5, 1.0]
color = [1.0, 1.0, 1.0]
intensity = 1.0'
cat > /tmp/placed/grid.toml <<TOML
$head
[shapes.cube]
kind = "gltf"
file = "AnimatedMorphCube.gltf"
[[objects]]
shape = "cube"
translate = [-1.5, 1.0, 0.0]
scale = 0.5
[[grids]]
shape = "cube"
materials = [""]
count = [2, 1, 1]
origin = [-1.0, -1.5, 0.0]
spacing = [2.5, 0.0, 0.0]
scale = 0.5
TOML
cat > /tmp/placed/two.toml <<TOML
$head
[shapes.cube]
kind = "gltf"
file = "AnimatedMorphCube.gltf"
[shapes.skin]
kind = "gltf"
file = "simple_skin.gltf"
[[objects]]
shape = "cube"
translate = [-2.0, 0.0, 0.0]
scale = 0.8
[[objects]]
shape = "skin"
translate = [1.0, -1.0, 0.0]
scale = 1.0
TOML
# The grid's models moved by the scene's own [animation] while their clips play.
cat /tmp/placed/grid.toml - > /tmp/placed/anim.toml <<TOML
[animation]
frames = 33
fps = 8.0
[[animation.tracks]]
target = "object 0"
property = "translate"
keys = [{ time = 0.0, value = [-1.5, 1.0, 0.0] }, { time = 4.0, value = [1.5, 1.0, 0.0] }]
[[animation.motions]]
kind = "spin"
target = "grid 0"
degrees_per_second = [0.0, 0.0, 20.0]
TOML
for s in grid two anim; do
  $T --fps 8 compare /tmp/placed/$s.toml --frames all --out-dir /tmp/cmp-$s > $R/compare-$s.log 2>&1
  echo "== compare $s --frames all: exit $?"; tail -4 $R/compare-$s.log
done
$T --fps 8 render /tmp/placed/two.toml --frames all --out /tmp/two.png > $R/render-two.log 2>&1
echo "== render two --frames all: exit $?"; tail -3 $R/render-two.log
cp /tmp/two-0000.png /tmp/two-0016.png $R/ 2>/dev/null
$T compare fuzz/corpus/gltf/quantized.gltf --width 1920 --height 1080 --out-dir /tmp/cmp-q > $R/compare-quantized.log 2>&1
echo "== compare quantized: exit $?"; tail -3 $R/compare-quantized.log
# Last, as the longest to write: ten million triangles.
python3 bench/deforming.py still 2238 /tmp/sheets/still-2238
TWINRAY_MAX_MESH_BYTES=400000000 /usr/bin/time -v $T render /tmp/sheets/still-2238.gltf --width 1920 --height 1080 \
  --out /tmp/still.png > $R/still-2238.log 2>&1
echo "== still-2238: exit $?"; grep -E "loaded|at its peak|Maximum resident|Elapsed" $R/still-2238.log
rm -rf /tmp/sheets
cd $OUT && tar czf placed-$(date +%s).tgz placed && rm -rf placed
