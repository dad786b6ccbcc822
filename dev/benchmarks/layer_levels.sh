#!/usr/bin/env bash
# The second model's forward pass (WHENet, 224x224) at every instruction-set level this CPU runs: hkf's
# layers (.models/whenet_fast.onnx, HKF_SIMD forcing the level) beside OpenCV's own layers on the plain
# graph (.models/whenet.onnx) with OpenCV held to the same level (OPENCV_CPU_DISABLE: the features above
# it), so that each row is what a CPU of that level would run; then onnxruntime on the plain graph at this
# CPU's full level, for scale. Medians of RUNS passes (default 40), on 1 and 2 threads, one level after
# another in one run; the CPU's name and flags first.
# usage: layer_levels.sh BUILD_DIR [RUNS]
set -euo pipefail
build=$(cd "$1" && pwd)
runs=${2:-40}
root=$(cd "$(dirname "$0")/../.." && pwd)
models=$root/.models
bench=$build/dev/benchmarks/hkf-bench-layers

opencv_disable() { # the OpenCV features a CPU of this level lacks (opencv_cpu_levels.txt)
  awk -v level="$1" '$1 == level { print $2 }' "$root/dev/benchmarks/opencv_cpu_levels.txt"
}
forward_ms() { # forward_ms LEVEL GRAPH THREADS: the median pass, or nothing when this CPU cannot run LEVEL
  HKF_SIMD=$1 OPENCV_CPU_DISABLE=$(opencv_disable "$1") "$bench" "$models/$2.onnx" 224 224 "$runs" "$3" 2>/dev/null |
    sed -n '1s/.*forward pass \([0-9.]*\) ms.*/\1/p'
}

cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)
flags=$(grep -m1 '^flags' /proc/cpuinfo | tr ' ' '\n' | grep -E '^(sse2|sse4_2|avx|avx2|fma|avx512f|avx512bw|avx512vl|asimd)$' | tr '\n' ' ')
echo "## The second model's forward pass per instruction-set level"
echo
echo "CPU: ${cpu:-$(uname -m)}, $(nproc) cores; flags: ${flags:-none of the vector ones}. WHENet 224x224, median of $runs passes."
echo
echo "| level | threads | hkf's layers | OpenCV's own layers, same level | hkf / OpenCV |"
echo "| --- | ---: | ---: | ---: | ---: |"
slower=0
machine=$(uname -m)
levels="sse2"
[ "$machine" = x86_64 ] && levels="avx512 avx2 sse2"
[ "$machine" = aarch64 ] && levels="neon"
for level in $levels; do
  for threads in 1 2; do
    ours=$(forward_ms "$level" whenet_fast "$threads")
    if [ -z "$ours" ]; then
      echo "| $level | $threads | (this CPU cannot run it) | | |"
      break
    fi
    theirs=$(forward_ms "$level" whenet "$threads")
    ratio=$(awk -v a="$ours" -v b="$theirs" 'BEGIN { printf "%.2f", a / b }')
    awk -v r="$ratio" 'BEGIN { exit !(r >= 1) }' && slower=1
    echo "| $level | $threads | $ours ms | $theirs ms | ${ratio}× |"
  done
done
echo
if [ -x "$root/.venv/bin/python" ]; then
  "$root/.venv/bin/python" - "$models/whenet.onnx" "$runs" <<'PY'
import statistics, sys, time
import numpy as np
import onnxruntime
options = onnxruntime.SessionOptions()
options.intra_op_num_threads = 2
session = onnxruntime.InferenceSession(sys.argv[1], options, providers=["CPUExecutionProvider"])
spec = session.get_inputs()[0]
x = np.random.RandomState(0).rand(*spec.shape).astype(np.float32)
for _ in range(5):
    session.run(None, {spec.name: x})
times = []
for _ in range(int(sys.argv[2])):
    t0 = time.perf_counter()
    session.run(None, {spec.name: x})
    times.append(1000 * (time.perf_counter() - t0))
print(f"onnxruntime {onnxruntime.__version__} on whenet.onnx, 2 threads, this CPU's full level: "
      f"{statistics.median(times):.2f} ms (median of {len(times)})")
PY
fi
if [ "$slower" = 1 ]; then
  echo "layer_levels: hkf's layers are not faster than OpenCV's own at some level above" >&2
  exit 1
fi
