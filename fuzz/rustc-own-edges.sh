#!/bin/sh
# A RUSTC_WRAPPER for minimising the corpus: rustc, without coverage instrumentation for every
# crate but twinray's own (twinray-host, twinray-shared, twinray-compile) and the fuzz targets, so that
# a merge keeps the inputs that reach new edges of twinray's code, not of the JSON, image and
# TOML parsers it calls (docs/testing.md, "Fuzzing"). Fuzz runs themselves do not use it.
#   RUSTC_WRAPPER=$PWD/rustc-own-edges.sh cargo +nightly-2026-08-15 fuzz build -s none -O --target-dir target/own-edges
rustc="$1"; shift
name=""; bin=0; prev=""
for a in "$@"; do
  [ "$prev" = "--crate-name" ] && name="$a"
  [ "$prev" = "--crate-type" ] && [ "$a" = bin ] && bin=1
  prev="$a"
done
case "$name" in
  twinray_host|twinray_shared|twinray_compile) exec "$rustc" "$@" ;;
esac
[ $bin = 1 ] && exec "$rustc" "$@"
# Every other crate: drop the sancov pass and its options.
set -- "$@" END
while [ "$1" != END ]; do
  a="$1"; shift
  case "$a" in
    -Cpasses=sancov-module|-Cllvm-args=-sanitizer-coverage*) continue ;;
    -C) case "$1" in passes=sancov-module|llvm-args=-sanitizer-coverage*) shift; continue ;; esac ;;
  esac
  set -- "$@" "$a"
done
shift
exec "$rustc" "$@"
