#!/usr/bin/env bash
# hkf-estimator's error paths: a missing or corrupt model, a bad description, missing labels, bad arguments;
# and its layers at each instruction-set level agreeing on real images (its figures on real data:
# estimator_dataset_test.sh).
# usage: estimator_cli_test.sh BUILD_DIR SOURCE_DIR DATA_DIR
set -euo pipefail
build=$1 source=$2 data=$3
est=$build/estimator/hkf-estimator
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

expect_error() { # expect_error PATTERN COMMAND...: non-zero exit, PATTERN in stderr
  local pattern=$1
  shift
  if "$@" >/dev/null 2>"$work/err.txt"; then fail "succeeded: $*"; fi
  grep -q "$pattern" "$work/err.txt" || { cat "$work/err.txt" >&2; fail "no '$pattern' in the error of: $*"; }
}
mkdir -p "$work/empty" "$work/corrupt" "$work/specs"
head -c 4096 /dev/urandom >"$work/corrupt/whenet_fast.onnx"
printf 'file = whenet.onnx\ninput = 224 224\ndecoder = angle_bins\nwarp = 9\n' >"$work/specs/bad.model"
expect_error "whenet_fast.onnx is missing" "$est" --dataset "$data" --predictions "$work/x.csv" --model whenet --models-dir "$work/empty"
expect_error "not a readable ONNX model" "$est" --dataset "$data" --predictions "$work/x.csv" --model whenet --models-dir "$work/corrupt"
expect_error "bad.model:4: unknown key 'warp'" "$est" --dataset "$data" --predictions "$work/x.csv" --model bad --spec-dir "$work/specs"
expect_error "no model description" "$est" --dataset "$data" --predictions "$work/x.csv" --model nosuch
expect_error "labels.csv" "$est" --dataset "$work/empty" --predictions "$work/x.csv"
expect_error "limit" "$est" --dataset "$data" --predictions "$work/x.csv" --limit zero
expect_error "needs --predictions" "$est" --dataset "$data"
expect_error "crop is live or labels" "$est" --dataset "$data" --predictions "$work/x.csv" --crop boxes
expect_error "either --source SRC or --dataset DIR" "$est" --limit 3
expect_error "detector is short, full or retina" "$est" --source x --detector medium
expect_error "region wants" "$est" --source x --region 1,2,3
# the layers' instruction-set level: HKF_SIMD names one this CPU runs (OpenCV's OPENCV_CPU_DISABLE plays a CPU
# without AVX-512 or AVX2), anything else is refused before a model is read
expect_error "HKF_SIMD='bogus' is not a level (.*sse2 or default)" env HKF_SIMD=bogus "$est" --dataset "$data" --predictions "$work/simd.csv"
expect_error "HKF_SIMD=avx2: this CPU cannot run it (it runs avx and below)" \
  env HKF_SIMD=avx2 OPENCV_CPU_DISABLE=AVX512F,AVX2 "$est" --dataset "$data" --predictions "$work/simd.csv"
expect_error "HKF_SIMD=avx: this CPU cannot run it (it runs sse2 and below)" \
  env HKF_SIMD=avx OPENCV_CPU_DISABLE=AVX512F,AVX2,FMA3,AVX "$est" --dataset "$data" --predictions "$work/simd.csv"
[ ! -e "$work/simd.csv" ] || fail "a refused run wrote its predictions"
"$est" --dataset "$data" --crop labels --predictions "$work/p.csv" --limit 20 --model whenet --second-model none >/dev/null 2>&1 ||
  fail "WHENet on 20 images at the CPU's best level"
HKF_SIMD=sse2 "$est" --dataset "$data" --crop labels --predictions "$work/sse2.csv" --limit 20 --model whenet --second-model none \
  2>"$work/sse2.err" >/dev/null
grep -q "own layers at sse2" "$work/sse2.err" || fail "the start-up line does not name the level forced"
# the same angles at the baseline as at the CPU's best level, to a thousandth of a degree
paste -d, <(head -21 "$work/p.csv") "$work/sse2.csv" | awk -F, 'NR > 1 {
  if ($1 != $5) bad = 1
  for (i = 2; i <= 4; ++i) { d = $i - $(i + 4); if (d < 0) d = -d; if (d > worst) worst = d }
} END { printf "sse2 against the best level: largest difference %.5f deg\n", worst; exit bad || worst > 0.001 }' ||
  fail "the sse2 layers' angles differ from the best level's"
level_taken() { # level_taken OPENCV_CPU_DISABLE: the level a CPU without those features takes
  OPENCV_CPU_DISABLE=$1 "$est" --dataset "$data" --predictions "$work/y.csv" --limit 1 2>&1 >/dev/null |
    sed -n 's/.*own layers at \([a-z0-9]*\) .*/\1/p'
}
[ "$(level_taken AVX512F,AVX2)" = avx ] || fail "a CPU with AVX but not AVX2 does not take avx"
[ "$(level_taken AVX512F,AVX2,FMA3,AVX)" = sse2 ] || fail "a CPU without AVX does not take sse2"
grep -q "usage: hkf-estimator" <<<"$("$est" --help)" || fail "--help"
echo "estimator_cli_test: all checks passed"
