#!/usr/bin/env bash
# The per-level benchmark script on a CPU without AVX-512 (on one it stopped with an empty table and
# exit 1): played here with HKF_PLAY_CPU_LEVEL=avx2, so the avx512 level is one the CPU cannot run. Every level
# gets its row, the script goes on to the end and exits 0 where hkf's layers are faster than OpenCV's own; and a
# benchmark that fails otherwise (exit 1) stops it with exit 1, never an empty table taken for a result.
# usage: layer_levels_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd)
script=$source/dev/benchmarks/layer_levels.sh
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; cat "$work/out.txt" >&2; exit 1; }
status=0
HKF_PLAY_CPU_LEVEL=avx2 "$script" "$build" 3 >"$work/out.txt" 2>&1 || status=$?
cat "$work/out.txt"
grep -q "Played as a CPU of level avx2" "$work/out.txt" || fail "the played level is not said"
grep -q "^| avx512 | 1 | (this CPU cannot run it)" "$work/out.txt" || fail "no row for the level the CPU lacks"
for level in avx2 avx sse2; do
  for threads in 1 2; do
    grep -Eq "^\| $level \| $threads \| [0-9.]+ ms \| [0-9.]+ ms \| [0-9.]+× \| ([0-9.]+ ms \| [0-9.]+×|\(cannot be held to this level here\) \|) \|$" "$work/out.txt" ||
      fail "no figures for $level on $threads thread(s)"
  done
done
grep -q "onnxruntime" "$work/out.txt" || fail "the script stopped before onnxruntime's line"
if grep -q "not faster than OpenCV's own" "$work/out.txt"; then
  [ "$status" = 1 ] || fail "slower than OpenCV's own at some level, but exit $status"
else
  [ "$status" = 0 ] || fail "exit $status"
fi
# a benchmark that fails for another reason (exit 1): the script says so and exits 1
printf '#!/bin/sh\necho "hkf-bench-layers: cannot load model file" >&2\nexit 1\n' >"$work/broken"
chmod +x "$work/broken"
status=0
HKF_BENCH_LAYERS=$work/broken "$script" "$build" 3 >"$work/out.txt" 2>&1 || status=$?
[ "$status" = 1 ] || fail "a broken benchmark: exit $status"
grep -q "the benchmark failed at avx512 (exit 1)" "$work/out.txt" || fail "a broken benchmark is not said"
echo "layer_levels_test: every level's row on a CPU played without AVX-512; a broken benchmark stops it"
