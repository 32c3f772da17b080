# Issue 15, run 19: every module of a set through spirv-opt (Debian spirv-tools 2023.1).
export LD_LIBRARY_PATH=$PWD/target/twinray-bench/lib
T=$PWD/target/twinray-bench/bin/twinray
export __GL_SHADER_DISK_CACHE=0
I=target/twinray-bench/i15
O=$I/opt
c() { s=$1; shift; echo "== $s $*"; $T --threads 1 compare $I/$s.toml "$@" --width 1920 --height 1080 --runs 20 --warmup 3 --out-dir /tmp/cmp | grep -E "ratio|  a = |  b = |rmse|FAIL"; }
for s in showcase-16 cone-16 cylinder-16 torus-16 sphere-16 plane-16; do
  c $s --a rust --b glsl
  c $s --a $O/O_rust --b glsl
  c $s --a $O/inl_rust --b glsl
  c $s --a $O/O_rust --b $O/O_glsl
  c $s --a $O/O_glsl --b glsl
done
