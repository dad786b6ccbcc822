#!/usr/bin/env bash
# The second model's forward pass (WHENet, 224x224) at every instruction-set level this CPU runs: hkf's
# layers (.models/whenet_fast.onnx, HKF_SIMD forcing the level) beside OpenCV's own layers on the plain
# graph (.models/whenet.onnx) with OpenCV held to the same level (OPENCV_CPU_DISABLE: the features above
# it), and onnxruntime on the plain graph held to the same level, so that each row is what a CPU of that level
# would run. onnxruntime's kernels ask the CPU itself (CPUID), so it is held by cpu_level_mask.c (preloaded; the
# kernel's CPUID faulting, flag cpuid_fault): at avx2 the CPU reports no AVX-512; at avx, no AVX2, FMA or F16C
# (Sandy Bridge); at sse2, no AVX (x86-64-v2:
# NumPy's wheels refuse a CPU below it, so onnxruntime's Python cannot be played lower), and each figure is
# checked against the features the process reported. Where it cannot be held (no faulting, no library), the row
# says so. Medians of RUNS passes (default 40), on 1 and 2 threads, one level after another in one run, the
# three back to back in each row; the CPU's name and flags first.
# A level this CPU lacks gets its row ("this CPU cannot run it") and the script goes on; it exits 0 when hkf's
# layers are faster than OpenCV's own at every level the CPU runs. HKF_PLAY_CPU_LEVEL=avx2 (or sse2) plays a CPU
# of that level: OpenCV is told the features above it are missing, and hkf's layers ask OpenCV what the CPU has,
# so the levels above are ones "this CPU cannot run" (tests/benchmarks/layer_levels_test.sh: a CPU without
# AVX-512 on one that has it). HKF_BENCH_LAYERS names another benchmark program.
# usage: layer_levels.sh BUILD_DIR [RUNS]
set -euo pipefail
build=$(cd "$1" && pwd)
runs=${2:-40}
root=$(cd "$(dirname "$0")/../.." && pwd)
models=$root/.models
bench=${HKF_BENCH_LAYERS:-$build/dev/benchmarks/hkf-bench-layers}

opencv_disable() { # the OpenCV features a CPU of this level lacks (opencv_cpu_levels.txt)
  awk -v level="$1" '$1 == level { print $2 }' "$root/dev/benchmarks/opencv_cpu_levels.txt"
}
forward_ms() { # forward_ms LEVEL GRAPH THREADS: the median pass, or nothing when this CPU cannot run LEVEL
  local text status=0
  local disable
  disable=$(opencv_disable "$1")
  [ -n "${HKF_PLAY_CPU_LEVEL:-}" ] && disable="$disable${disable:+,}$(opencv_disable "$HKF_PLAY_CPU_LEVEL")"
  text=$(HKF_SIMD=$1 OPENCV_CPU_DISABLE=$disable "$bench" "$models/$2.onnx" 224 224 "$runs" "$3" 2>/dev/null) || status=$?
  [ "$status" = 0 ] || [ "$status" = 2 ] || { echo "layer_levels: the benchmark failed at $1 (exit $status)" >&2; exit 1; }
  sed -n '1s/.*forward pass \([0-9.]*\) ms.*/\1/p' <<<"$text"  # exit 2: the CPU cannot run the level: nothing
}

mask=$build/dev/benchmarks/libhkf-cpu-level-mask.so
python=$root/.venv/bin/python
onnxruntime_ms() { # onnxruntime_ms LEVEL THREADS: the median pass held to LEVEL, or why it cannot be
  local played=off want
  case $1 in
    avx512) want="1 1 1" ;;
    avx2) played=avx2 want="1 1 0" ;;
    avx) played=avx want="1 0 0" ;;
    sse2) played=sse4_2 want="0 0 0" ;;
  esac
  # a CPU without the features above the level is that level already
  [ "$1" = avx2 ] && ! grep -qw avx512f /proc/cpuinfo && played=off
  [ "$1" = avx ] && ! grep -qw avx2 /proc/cpuinfo && ! grep -qw fma /proc/cpuinfo && played=off
  [ "$1" = sse2 ] && ! grep -qw avx /proc/cpuinfo && played=off
  [ -x "$python" ] || { echo "(no .venv: ./run setup)"; return; }
  if [ "$played" != off ] && { [ ! -f "$mask" ] || ! grep -qw cpuid_fault /proc/cpuinfo; }; then
    echo "(cannot be held to this level here)"
    return
  fi
  local line
  line=$(HKF_PLAY_CPUID_LEVEL=$played LD_PRELOAD=$([ "$played" != off ] && echo "$mask") \
    "$python" "$root/dev/benchmarks/onnxruntime_pass.py" "$models/whenet.onnx" "$2" "$runs") ||
    { echo "layer_levels: onnxruntime failed at $1" >&2; exit 1; }
  [ "${line#* }" = "$want" ] || { echo "layer_levels: onnxruntime saw CPU features '${line#* }' at $1, not '$want'" >&2; exit 1; }
  echo "${line%% *} ms"
}

cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)
flags=$(grep -m1 '^flags' /proc/cpuinfo | tr ' ' '\n' | grep -E '^(sse2|sse4_2|avx|avx2|fma|avx512f|avx512bw|avx512vl|asimd)$' | tr '\n' ' ')
echo "## The second model's forward pass per instruction-set level"
echo
played=""
[ -n "${HKF_PLAY_CPU_LEVEL:-}" ] && played=" Played as a CPU of level $HKF_PLAY_CPU_LEVEL (OpenCV told the features above it are missing)."
echo "CPU: ${cpu:-$(uname -m)}, $(nproc) cores; flags: ${flags:-none of the vector ones}.$played WHENet 224x224, median of $runs passes."
echo
echo "| level | threads | hkf's layers | OpenCV's own layers, same level | hkf / OpenCV | onnxruntime, same level | hkf / onnxruntime |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: |"
slower=0
machine=$(uname -m)
levels="sse2"
[ "$machine" = x86_64 ] && levels="avx512 avx2 avx sse2"
[ "$machine" = aarch64 ] && levels="neon"
for level in $levels; do
  for threads in 1 2; do
    ours=$(forward_ms "$level" whenet_fast "$threads")
    if [ -z "$ours" ]; then
      echo "| $level | $threads | (this CPU cannot run it) | | | | |"
      break
    fi
    theirs=$(forward_ms "$level" whenet "$threads")
    ratio=$(awk -v a="$ours" -v b="$theirs" 'BEGIN { printf "%.2f", a / b }')
    awk -v r="$ratio" 'BEGIN { exit !(r >= 1) }' && slower=1
    peer=$(onnxruntime_ms "$level" "$threads")
    peer_ratio=""
    [[ $peer == *" ms" ]] && peer_ratio=$(awk -v a="$ours" -v b="${peer% ms}" 'BEGIN { printf "%.2f×", a / b }')
    echo "| $level | $threads | $ours ms | $theirs ms | ${ratio}× | $peer | $peer_ratio |"
  done
done
echo
ort=$("$python" -c 'import onnxruntime; print(onnxruntime.__version__)' 2>/dev/null || echo "?")
echo "onnxruntime $ort on whenet.onnx; its sse2 row is x86-64-v2 (SSE4.2, no AVX), the lowest its Python runs on."
if [ "$slower" = 1 ]; then
  echo "layer_levels: hkf's layers are not faster than OpenCV's own at some level above" >&2
  exit 1
fi
