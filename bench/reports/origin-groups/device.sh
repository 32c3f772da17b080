#!/bin/sh
# The local origin per group of rays (docs/numerics.md, "The local origin") on the GPU machine,
# from the repository root with the bundle (`cargo xtask bundle`, carried as
# target/twinray-bench.tar.gz):
#   sh bench/reports/origin-groups/device.sh NAME [RANDOM_CASES]
# 1. the hard-case suite, both sets, against its targets;
# 2. every case of probes/stability/ and of probes/ (but mesh-edges.toml, whose model is an
#    installed Debian file) at the chosen origins against world coordinates, both sets;
# 3. RANDOM_CASES (default 200) random cases of far-apart ray groups, the same comparison;
# 4. bench/reports/origin-groups/eye-secondary-rays.toml at the eye (as a render traces it), at the chosen origins
#    and at world coordinates, both sets.
# Everything lands in $OUT/NAME.tgz.
set -u
[ -x /tmp/twinray-bench/bin/twinray ] || tar xzf target/twinray-bench.tar.gz -C /tmp
B=/tmp/twinray-bench
export LD_LIBRARY_PATH=$B/lib PATH=$B/bin:$PATH
name=$1
cases=${2:-200}
R=$OUT/$name
mkdir -p $R /tmp/probes
twinray info > $R/info.txt 2>&1
step() { s=$(date +%s); "$@"; echo "== $*: exit $?, $(( $(date +%s) - s )) s"; }
step sh -c "twinray stability --json > $R/stability.json 2> $R/stability.err"
step sh -c "twinray stability --against-world > $R/against-stability.txt 2> $R/against-stability.err"
ls probes/*.toml | grep -v mesh-edges | xargs -I{} cp {} /tmp/probes/
step sh -c "twinray stability --against-world --dir /tmp/probes > $R/against-probes.txt 2> $R/against-probes.err"
step sh -c "twinray stability --against-world --random $cases --json > $R/against-random.json 2> $R/against-random.err"
for o in eye local world; do
  sed "s/^gpu_origin = \"eye\"/gpu_origin = \"$o\"/" bench/reports/origin-groups/eye-secondary-rays.toml > /tmp/eye-$o.toml
  for set in rust glsl; do
    twinray probe /tmp/eye-$o.toml --shaders $set > $R/eye-$o-$set.txt 2>&1
    echo "== eye-secondary-rays $o $set: exit $?"
  done
done
tail -n 3 $R/against-stability.txt $R/against-probes.txt
cd $OUT && tar czf $name.tgz $name && rm -rf $name
