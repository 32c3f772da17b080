# Issue 53: the ClearCoat model at 1 spp at three image sizes, to tell a cost per ray (the
# ratio stays) from one per launch (the milliseconds stay). Run from the repository root with
# the bundle and the model in target/models (see ../issue53-table/README.md):
#   sh bench/reports/issue53-any-hit/resolutions.sh NAME SETS [BENCH FLAGS...]
# raw/r1: NAME r1, SETS glsl,rust,rust,raygen=glsl; raw/r2: the other label order, with --null.
set -u
name=$1 sets=$2
shift 2
extra="$*"
[ -x /tmp/twinray-bench/bin/twinray ] || tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench; export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH; T=$B/bin/twinray
R=$OUT/$name; mkdir -p $R; $T info > $R/info.txt 2>&1
scene=target/models/ClearCoat-glTF/ClearCoatTest.gltf
# SIZES (WxH, space-separated) overrides the three sizes; raw/r3 is SIZES="256x256 64x64".
for wh in ${SIZES:-1920x1080 3840x2160 960x540}; do
  w=${wh%x*} h=${wh#*x}; out=$R/res-${w}x$h; s=$(date +%s)
  $T bench $scene --sets "$sets" $extra --width $w --height $h \
    --spp 1 --runs 10 --warmup 2 --placements 1 --processes 8 --alone-in devices \
    --reference-spp 16 --shadow-spp none --probes none --images none --cache /tmp/refs --out $out > $out.log 2>&1
  echo "== ${w}x$h: exit $?, $(( $(date +%s) - s )) s"; grep " / " $out.log | cut -c1-120
done
cd $OUT && tar czf $name.tgz $(find $name -name results.json -o -name '*.txt' -o -name '*.log') && rm -rf $name
