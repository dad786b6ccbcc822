#!/usr/bin/env bash
# libhkf on a Cortex-M, in an emulator: hkf-estimator's raw poses of a shared
# clip -> the x86 double build's output (make_mcu_sequence) -> libhkf and
# target_test.c cross-compiled for CPU with REAL -> qemu-system-arm with
# semihosting. Passes when the target's angles are within the tolerance of
# the double build's. Exit 77 (skipped) without the toolchain or qemu.
# REAL cmsis_dsp runs, instead of libhkf, the same filter written with
# CMSIS-DSP's matrix functions (cmsis_dsp_filter.c; float, Cortex-M4F) against
# the same double build; it needs dev/mcu/fetch_cmsis_dsp.sh's sources.
# TOLERANCE_DEG: with the paper's settings; DEFAULTS_TOLERANCE_DEG: with the defaults.
# usage: run_target_test.sh BUILD_DIR SOURCE_DIR CPU REAL TOLERANCE_DEG DEFAULTS_TOLERANCE_DEG
set -euo pipefail
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd) cpu=$3 real=$4 tolerance=$5 defaults_tolerance=$6
for tool in arm-none-eabi-gcc qemu-system-arm; do
  command -v "$tool" >/dev/null || { echo "SKIP: $tool is not installed (scripts/setup.sh installs it)"; exit 77; }
done
program=hkf_target_test extra=()
if [ "$real" = cmsis_dsp ]; then
  cmsis=$source/.third_party/cmsis-dsp
  [ -s "$cmsis/Include/arm_math.h" ] \
    || { echo "SKIP: no CMSIS-DSP sources in $cmsis (dev/mcu/fetch_cmsis_dsp.sh, run by scripts/setup.sh)"; exit 77; }
  program=hkf_cmsis_dsp_test extra=(-DHKF_CMSIS_DSP_DIR="$cmsis")
fi
clip=$source/../shared/data/videos/d10.mp4
work=$build/mcu/$cpu-$real
mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }

if [ ! -s "$build/mcu/sequence.csv" ]; then  # made once, shared by the targets
  "$build/estimator/hkf-estimator" --source "$clip" --lcm-url "file://$work/raw.lcmlog?mode=w" >/dev/null 2>&1 \
    || fail "hkf-estimator on $clip"
  "$source/.venv/bin/python" "$source/tests/mcu/raw_log_to_csv.py" "$work/raw.lcmlog" "$build/lcmtypes/python" \
    "$work/sequence.csv"
  mv "$work/sequence.csv" "$build/mcu/sequence.csv"
fi
"$build/tests/make_mcu_sequence" "$build/mcu/sequence.csv" "d10.mp4" "$tolerance" "$defaults_tolerance" \
  "$work/sequence.h" >/dev/null
# Cortex-M0 parts have little flash (16-256 KiB): built for size there, for speed elsewhere
build_type=Release
[ "$cpu" = cortex-m0 ] && build_type=MinSizeRel
cmake -S "$source" -B "$work/build" -G Ninja -DCMAKE_TOOLCHAIN_FILE="$source/cmake/arm-none-eabi.cmake" -DHKF_WARNINGS_AS_ERRORS=ON \
  -DHKF_CPU="$cpu" -DHKF_REAL="${real/cmsis_dsp/float}" -DCMAKE_BUILD_TYPE=$build_type \
  -DHKF_MCU_SEQUENCE="$work/sequence.h" "${extra[@]}" >/dev/null \
  || fail "configuring the $cpu build"
cmake --build "$work/build" >"$work/build.log" 2>&1 || { cat "$work/build.log" >&2; fail "building for $cpu"; }
board=$(cat "$work/build/tests/mcu/board.txt")
echo "running on qemu-system-arm -M $board ($cpu, $real)"
status=0
timeout 300 qemu-system-arm -M "$board" -nographic -monitor none -serial none -semihosting-config enable=on,target=native \
  -icount shift=6 -kernel "$work/build/tests/mcu/$program.elf" >"$work/output.txt" 2>&1 || status=$?
cat "$work/output.txt"
[ "$status" = 0 ] || fail "the target test on $cpu ($real) exited $status"
grep -q "largest error against the x86 double build" "$work/output.txt" || fail "no result from the target"
