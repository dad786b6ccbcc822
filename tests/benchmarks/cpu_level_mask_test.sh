#!/usr/bin/env bash
# cpu_level_mask.c: a program preloaded with it at a played level sees the CPU of that level through CPUID itself
# (NumPy's own CPU detection is the witness: it asks CPUID as onnxruntime's kernels do), the full CPU with "off",
# and a level it does not know ends the program with exit 3 and a message. Skipped (77) on a CPU without CPUID
# faulting or without AVX-512 (nothing to hold back), or without the project's .venv.
# usage: cpu_level_mask_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd)
mask=$build/dev/benchmarks/libhkf-cpu-level-mask.so
python=$source/.venv/bin/python
grep -qw cpuid_fault /proc/cpuinfo || { echo "SKIP: no CPUID faulting on this CPU"; exit 77; }
grep -qw avx512f /proc/cpuinfo || { echo "SKIP: no AVX-512 to hold back on this CPU"; exit 77; }
[ -x "$python" ] || { echo "SKIP: no .venv (./run setup)"; exit 77; }
[ -f "$mask" ] || { echo "FAIL: $mask was not built" >&2; exit 1; }
seen() { # seen LEVEL: what NumPy finds, "AVX AVX2 AVX512F SSE42 FMA3 F16C" as 0/1
  HKF_PLAY_CPUID_LEVEL=$1 LD_PRELOAD=$mask "$python" -c '
from numpy._core._multiarray_umath import __cpu_features__ as f
print(" ".join(str(int(bool(f.get(n)))) for n in ("AVX", "AVX2", "AVX512F", "SSE42", "FMA3", "F16C")))'
}
fail() { echo "FAIL: $*" >&2; exit 1; }
[ "$(seen off)" = "1 1 1 1 1 1" ] || fail "off: NumPy saw '$(seen off)', not the full CPU"
[ "$(seen avx2)" = "1 1 0 1 1 1" ] || fail "avx2: NumPy saw '$(seen avx2)', not AVX2 without AVX-512"
[ "$(seen avx)" = "1 0 0 1 0 0" ] || fail "avx: NumPy saw '$(seen avx)', not AVX without AVX2, FMA or F16C"
[ "$(seen sse4_2)" = "0 0 0 1 0 0" ] || fail "sse4_2: NumPy saw '$(seen sse4_2)', not SSE4.2 without AVX"
status=0
message=$(HKF_PLAY_CPUID_LEVEL=avx3 LD_PRELOAD=$mask "$python" -c 'print("ran")' 2>&1) || status=$?
[ "$status" = 3 ] || fail "an unknown level: exit $status ($message)"
grep -q "must be avx2, avx, sse4_2 or off" <<<"$message" || fail "an unknown level is not said: $message"
# a real fault in the program is still a crash, not taken for a CPUID
status=0
(HKF_PLAY_CPUID_LEVEL=avx2 LD_PRELOAD=$mask "$python" -c 'import ctypes; ctypes.string_at(0)') 2>/dev/null || status=$?
[ "$status" = 139 ] || fail "a null read under the mask: exit $status, not a segmentation fault (139)"
echo "cpu_level_mask_test: avx2, avx and sse4_2 played through CPUID, off unchanged, a bad level refused, a real fault kept"
