#!/usr/bin/env bash
# hkf-estimator's evaluation mode on real data, and its error paths: a missing
# or corrupt model, a bad description, missing labels, bad arguments.
# usage: estimator_cli_test.sh BUILD_DIR SOURCE_DIR DATA_DIR
set -euo pipefail
build=$1 source=$2 data=$3
est=$build/estimator/hkf-estimator
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# real data: the first 100 AFLW2000 images; WHENet on the labelled face boxes, as its paper measured it
"$est" --dataset "$data" --crop labels --predictions "$work/p.csv" --limit 100 --model whenet | tee "$work/out.txt"
[ "$(wc -l <"$work/p.csv")" -eq 101 ] || fail "expected 100 predictions"
head -1 "$work/p.csv" | grep -qx "image,pitch_deg,yaw_deg,roll_deg" || fail "CSV header"
read -r pitch yaw roll < <(sed -n 's/MAE deg: pitch \([0-9.]*\), yaw \([0-9.]*\), roll \([0-9.]*\).*/\1 \2 \3/p' "$work/out.txt")
awk -v p="$pitch" -v y="$yaw" -v r="$roll" 'BEGIN { exit !(p < 6.5 && y < 6.5 && r < 6.5) }' ||
  fail "MAE $pitch/$yaw/$roll deg is far from WHENet's published ~5.4"

grep -q "(labelled face boxes): 100 images (0 unreadable, 0 without a face found)" "$work/out.txt" ||
  fail "WHENet given the labelled boxes must take every face"

# the default estimator on the same images, the default way: the live path (detector on the whole image)
"$est" --dataset "$data" --predictions "$work/m.csv" --limit 100 --model mesh_pnp --second-model none | tee "$work/mesh.txt"
grep -q "(live path: detector on the whole image)" "$work/mesh.txt" || fail "--dataset does not default to the live path"
grep -q "^faces not found: [0-9]*, of which the detector took another face: [0-9]*$" "$work/mesh.txt" ||
  fail "no count of faces not found on the live path"
read -r pitch yaw roll < <(sed -n 's/MAE deg: pitch \([0-9.]*\), yaw \([0-9.]*\), roll \([0-9.]*\).*/\1 \2 \3/p' "$work/mesh.txt")
awk -v p="$pitch" -v y="$yaw" -v r="$roll" 'BEGIN { exit !(p < 7 && y < 7 && r < 7) }' || fail "mesh_pnp MAE $pitch/$yaw/$roll deg"
missed=$(sed -n 's/.*, \([0-9]*\) without a face found.*/\1/p' "$work/mesh.txt")
[ "$missed" -le 20 ] || fail "mesh_pnp found no face in $missed of 100 images"
# by labelled yaw: three bins whose found faces add up to the images evaluated
[ "$(grep -c '^labelled |yaw| .* faces found' "$work/mesh.txt")" = 3 ] || fail "no per-yaw-bin lines"
found=$(sed -n 's/^labelled |yaw| .* images, *\([0-9]*\) faces found.*/\1/p' "$work/mesh.txt" | awk '{ s += $1 } END { print s }')
evaluated=$(sed -n 's/.* \([0-9]*\) within +-99 deg$/\1/p' "$work/mesh.txt")
[ "$found" = "$evaluated" ] || fail "the yaw bins hold $found faces, $evaluated were evaluated"

# both models' predictions fused as hkf_update_pair fuses them (dev/eval/fusion_on_aflw.py): every face
# either model found is estimated, and the fused error lies between the two models' (per image it is a
# weighted mean of theirs, so far below the worse one)
"$source/.venv/bin/python" "$source/dev/eval/fusion_on_aflw.py" --labels "$data/labels.csv" --limit 100 --mesh "$work/m.csv" \
  --whenet "$work/p.csv" --filter "$build/tools/hkf-filter" | tee "$work/fusion.txt"
"$source/.venv/bin/python" - "$work/fusion.txt" <<'PY' || fail "fusion_on_aflw.py"
import re, sys
rows = {m[1]: (float(m[2]), float(m[3])) for m in re.finditer(r"^\| (.+?) \|.*\| ([\d.]+) %, ([\d.]+)° \|$", open(sys.argv[1]).read(), re.M)}
mesh, whenet, fused = rows["mesh_pnp"], rows["whenet"], next(v for k, v in rows.items() if k.startswith("fused"))
assert fused[0] >= max(mesh[0], whenet[0]), (fused, mesh, whenet)
assert fused[1] < max(mesh[1], whenet[1]), (fused, mesh, whenet)
# the pipeline's row (mesh, WHENet fused in or alone at larger yaw): every face either found, and better than the worse
pipeline = next(v for k, v in rows.items() if k.startswith("the pipeline"))
assert pipeline[0] == fused[0] and pipeline[1] < max(mesh[1], whenet[1]), (pipeline, mesh, whenet)
PY

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
expect_error "HKF_SIMD=avx2: this CPU cannot run it (it runs sse2 and below)" \
  env HKF_SIMD=avx2 OPENCV_CPU_DISABLE=AVX512F,AVX2 "$est" --dataset "$data" --predictions "$work/simd.csv"
[ ! -e "$work/simd.csv" ] || fail "a refused run wrote its predictions"
HKF_SIMD=sse2 "$est" --dataset "$data" --crop labels --predictions "$work/sse2.csv" --limit 20 --model whenet --second-model none \
  2>"$work/sse2.err" >/dev/null
grep -q "own layers at sse2" "$work/sse2.err" || fail "the start-up line does not name the level forced"
# the same angles at the baseline as at the CPU's best level (the first run above), to a thousandth of a degree
paste -d, <(head -21 "$work/p.csv") "$work/sse2.csv" | awk -F, 'NR > 1 {
  if ($1 != $5) bad = 1
  for (i = 2; i <= 4; ++i) { d = $i - $(i + 4); if (d < 0) d = -d; if (d > worst) worst = d }
} END { printf "sse2 against the best level: largest difference %.5f deg\n", worst; exit bad || worst > 0.001 }' ||
  fail "the sse2 layers' angles differ from the best level's"
grep -q "own layers at $(OPENCV_CPU_DISABLE=AVX512F,AVX2 "$est" --dataset "$data" --predictions "$work/y.csv" --limit 1 2>&1 >/dev/null |
  sed -n 's/.*own layers at \([a-z0-9]*\) .*/\1/p')" <<<"own layers at sse2" || fail "a CPU without AVX2 does not take sse2"
grep -q "usage: hkf-estimator" <<<"$("$est" --help)" || fail "--help"
echo "estimator_cli_test: all checks passed"
