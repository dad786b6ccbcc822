#!/usr/bin/env bash
# The fault catalogue, part 4: the fifth hostile review (docs/reliability.md, "round 5"), on real data
# (a real clip's raw poses, AFLW2000 images, the shipped models): outputs refused by file identity (hard
# links to every kind of input, for every option that names an output), outputs that are no disk file
# (/proc, /sys, devices), damaged model files, a malformed OPENCV_IO_MAX_IMAGE_PIXELS, the estimator's
# process name, OpenCV's own error line. Each case fails without its fix.
# usage: faults_round5_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd)
python=$source/.venv/bin/python
estimator=$build/estimator/hkf-estimator filter=$build/tools/hkf-filter annotate=$build/estimator/hkf-annotate
simlog=$build/tools/hkf-simlog cmd=$build/tools/hkf-cmd
data=$source/../shared/data models=$source/.models
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# shellcheck source=expect_exit.sh
. "$source/tests/faults/expect_exit.sh"  # fail, expect_exit, said
sum() { sha256sum "$@" | sha256sum | cut -d' ' -f1; }
cd "$work"

# the inputs: a dataset (labels and images), a folder of images, a video, a raw log, a config
mkdir -p ds/images src
head -n 4 "$data/aflw2000/labels.csv" >ds/labels.csv
for image in $(tail -n +2 ds/labels.csv | cut -d, -f1); do cp "$data/aflw2000/images/$image" ds/images/; cp "$data/aflw2000/images/$image" src/; done
image=$(ls src | head -n 1)
"$estimator" --source "$data/videos/d3.mp4" --max-frames 20 --second-model none --lcm-url "file://$work/raw.lcmlog?mode=w" \
  >/dev/null 2>&1 || fail "the raw log"
cp "$data/videos/d3.mp4" clip.mp4
cp "$source/filter_node/hkf-filter.conf" filter.conf
"$filter" --offline raw.lcmlog filtered.lcmlog >/dev/null 2>&1 || fail "the filtered log"
inputs_sum=$(sum ds/labels.csv ds/images/* src/* clip.mp4 raw.lcmlog filter.conf)

echo "== 1. an output that is a hard link to an input is refused, for every option that names an output"
ln ds/labels.csv link_labels.csv
ln "ds/images/$image" link_image.csv
ln "src/$image" link_image.mp4
ln clip.mp4 link_clip.mp4
ln raw.lcmlog link_raw.lcmlog
ln filter.conf link_conf.csv
expect_exit 1 "--dataset DS --predictions LINK-TO-LABELS" "$estimator" --dataset ds --predictions link_labels.csv
said "is the same file as 'ds/labels.csv'"
expect_exit 1 "--dataset DS --predictions LINK-TO-AN-IMAGE" "$estimator" --dataset ds --predictions link_image.csv
said "is the same file as 'ds/images/$image'"
expect_exit 2 "--source SRC --annotate LINK-TO-AN-IMAGE" "$estimator" --source src --annotate link_image.mp4 --lcm-url memq://
said "is the same file as 'src/$image'"
expect_exit 2 "--source VIDEO --annotate LINK-TO-THE-VIDEO" "$estimator" --source clip.mp4 --annotate link_clip.mp4 --lcm-url memq://
ln "src/$image" link_image.lcmlog
expect_exit 1 "--source SRC --lcm-url file://LINK-TO-AN-IMAGE?mode=w" "$estimator" --source src --lcm-url "file://$work/link_image.lcmlog?mode=w"
said "is the same file as 'src/$image'"
ln "$models/whenet_fast.onnx" link_model.mp4 2>/dev/null || cp -l "$models/whenet_fast.onnx" link_model.mp4 2>/dev/null || true
if [ -e link_model.mp4 ]; then  # a hard link to a model file (the same filesystem as the models)
  expect_exit 2 "--annotate LINK-TO-A-MODEL" "$estimator" --source clip.mp4 --annotate link_model.mp4 --lcm-url memq://
  said "is the same file as"
fi
expect_exit 1 "hkf-filter --offline IN LINK-TO-IN" "$filter" --offline raw.lcmlog link_raw.lcmlog
expect_exit 1 "hkf-filter --config C --offline IN OUT --csv LINK-TO-C" "$filter" --config filter.conf --offline raw.lcmlog out.lcmlog --csv link_conf.csv
expect_exit 1 "hkf-filter --input-url file://IN --csv LINK-TO-IN" "$filter" --input-url "file://$work/raw.lcmlog" --csv link_raw.lcmlog
expect_exit 1 "hkf-annotate VIDEO RAW FILTERED LINK-TO-THE-VIDEO" "$annotate" clip.mp4 raw.lcmlog filtered.lcmlog link_clip.mp4
said "refusing to write over it"
expect_exit 1 "hkf-annotate ... --still 0 LINK-TO-THE-RAW-LOG" "$annotate" clip.mp4 raw.lcmlog filtered.lcmlog a.mp4 --still 0 link_raw.lcmlog
said "refusing to write over it"
[ "$(sum ds/labels.csv ds/images/* src/* clip.mp4 raw.lcmlog filter.conf)" = "$inputs_sum" ] || fail "an input changed"

echo "== 5. an output that is no disk file: /proc, /sys, a device - refused before anything is written"
# files where a write that got through would do no harm: this process's own name, a read-only attribute, the
# null devices (the review's /proc/sys/kernel/hostname was checked by hand, in a private UTS namespace)
for output in /proc/self/comm /sys/kernel/mm/transparent_hugepage/hpage_pmd_size /dev/full /dev/null; do
  [ -e "$output" ] || continue
  expect_exit 1 "hkf-filter --offline IN $output" "$filter" --offline raw.lcmlog "$output"
  said "refusing to write there\|an output must be a regular file"
  expect_exit 1 "hkf-filter --offline IN OUT --csv $output" "$filter" --offline raw.lcmlog out.lcmlog --csv "$output"
  expect_exit 1 "hkf-estimator --dataset DS --predictions $output" "$estimator" --dataset ds --predictions "$output"
  expect_exit 1 "hkf-simlog --out $output" "$simlog" --out "$output" --seconds 1
done
expect_exit 1 "hkf-cmd recenter --lcm-url file:///proc/self/comm?mode=w" "$cmd" recenter --lcm-url "file:///proc/self/comm?mode=w"
said "system filesystem"
expect_exit 2 "hkf-estimator --annotate /proc/sys/kernel/x.mp4" "$estimator" --source clip.mp4 --annotate /proc/sys/kernel/x.mp4 --lcm-url memq://

echo "== 2. a damaged model file: refused with the reason, exit 1, never a crash or a read past its end"
for damage in "short w_1" "short w_6" "short w_22" "huge w_22"; do
  set -- $damage
  mkdir "m_$1_$2"
  cp "$models"/*.onnx "$models"/canonical_face.txt "m_$1_$2/"
  "$python" "$source/tests/faults/damage_model.py" "$models/whenet_fast.onnx" "m_$1_$2/whenet_fast.onnx" "$1" "$2" >/dev/null
  expect_exit 1 "whenet_fast.onnx, $1 $2" "$estimator" --dataset ds --predictions p.csv --model whenet --models-dir "m_$1_$2"
  said "cannot load model file m_$1_$2/whenet_fast.onnx: tensor '$2'"
done
# OpenCV's own error line is not printed before hkf's (a graph OpenCV cannot import, whose tensors are whole)
"$python" - m_unknown.onnx <<'PY'
import sys
from onnx import TensorProto, helper
x = helper.make_tensor_value_info("x", TensorProto.FLOAT, [1, 3, 4, 4])
y = helper.make_tensor_value_info("y", TensorProto.FLOAT, None)
graph = helper.make_graph([helper.make_node("NoSuchOperator", ["x"], ["y"])], "g", [x], [y])
import onnx
onnx.save(helper.make_model(graph), sys.argv[1])
PY
mkdir m_unknown && cp "$models"/*.onnx "$models"/canonical_face.txt m_unknown/ && cp m_unknown.onnx m_unknown/whenet_fast.onnx
expect_exit 1 "a graph OpenCV cannot import" "$estimator" --dataset ds --predictions p.csv --model whenet --models-dir m_unknown
said "cannot load model file m_unknown/whenet_fast.onnx: not a readable ONNX model"
if grep -q "^\[ERROR" "$work/out.txt"; then cat "$work/out.txt" >&2; fail "OpenCV's own error line was printed"; fi

echo "== 4. a malformed OPENCV_IO_MAX_IMAGE_PIXELS: a clear error and exit 2, never an abort"
for value in "" abc 1e3 -5 0 33177601 18446744073709551616 99999999999999999999999; do
  expect_exit 2 "OPENCV_IO_MAX_IMAGE_PIXELS='$value'" env OPENCV_IO_MAX_IMAGE_PIXELS="$value" "$estimator" --source src --lcm-url memq://
  said "OPENCV_IO_MAX_IMAGE_PIXELS='$value' is not a whole number of pixels from 1 to 33177600"
  expect_exit 0 "OPENCV_IO_MAX_IMAGE_PIXELS='$value' hkf-estimator --version" env OPENCV_IO_MAX_IMAGE_PIXELS="$value" "$estimator" --version
  expect_exit 2 "OPENCV_IO_MAX_IMAGE_PIXELS='$value' hkf-annotate" env OPENCV_IO_MAX_IMAGE_PIXELS="$value" "$annotate" \
    clip.mp4 raw.lcmlog filtered.lcmlog a.mp4
done
expect_exit 0 "OPENCV_IO_MAX_IMAGE_PIXELS=1000000" env OPENCV_IO_MAX_IMAGE_PIXELS=1000000 "$estimator" --source src --lcm-url memq://
said "^hkf-estimator: 3 frames"

echo "== 6. the running estimator keeps its name (pgrep -x, pkill)"
"$estimator" --source "$data/videos/d3.mp4" --realtime --second-model none --lcm-url memq:// >named.txt 2>&1 &
running=$!
found=""
for _ in $(seq 100); do
  found=$(pgrep -x hkf-estimator | grep -x "$running" || true)
  [ -n "$found" ] && grep -q "HEAD_POSE_RAW on memq" named.txt && break
  sleep 0.1
done
kill -TERM "$running"
wait "$running" || true
[ -n "$found" ] || fail "pgrep -x hkf-estimator does not find the running estimator (pid $running; its name: $(cat /proc/$running/comm 2>/dev/null))"
echo "pgrep -x hkf-estimator: found pid $found"
cd - >/dev/null
echo "faults_round5_test: all checks passed"
