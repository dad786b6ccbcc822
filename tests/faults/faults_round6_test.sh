#!/usr/bin/env bash
# The fault catalogue, part 5: the sixth hostile review (docs/reliability.md, "round 6"), on real data (the
# shipped models, a real clip): a model whose tensor is given twice (protobuf merges the two), OpenCV's
# variables that it parses as it loads (every one that aborted before main), OPENCV_TRACE, hkf-track's logs
# over its programs' inputs, Ctrl-C in hkf-track's first moments, ports read one way by every program, a
# config's byte order mark, a status channel that is another's. Each case fails without its fix.
# usage: faults_round6_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd)
python=$source/.venv/bin/python
estimator=$build/estimator/hkf-estimator annotate=$build/estimator/hkf-annotate
data=$source/../shared/data models=$source/.models
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# shellcheck source=expect_exit.sh
. "$source/tests/faults/expect_exit.sh"  # fail, expect_exit, said
cd "$work"
mkdir -p ds/images
head -n 3 "$data/aflw2000/labels.csv" >ds/labels.csv
for image in $(tail -n +2 ds/labels.csv | cut -d, -f1); do cp "$data/aflw2000/images/$image" ds/images/; done

echo "== 1. a Constant's tensor given twice (INT8 [N] with N values, then FLOAT [1] with 4 bytes): protobuf merges"
echo "   them into FLOAT [N, 1] with 4 bytes, which OpenCV over-read (SIGSEGV); the check reads the merge"
mkdir m_merged
cp "$models"/*.onnx "$models"/canonical_face.txt m_merged/
"$python" - "$models/whenet_fast.onnx" m_merged/whenet_fast.onnx "$source/tests/fuzz" <<'PY'
import sys
sys.path.insert(0, sys.argv[3])
from protobuf_bytes import field, number, varint
n = 1 << 22
int8_part = number(1, n) + number(2, 3) + field(5, b"".join(varint(1) for _ in range(n)))
float_part = number(1, 1) + number(2, 1) + field(9, bytes(4))
attribute = field(1, b"value") + number(20, 4) + field(5, int8_part) + field(5, float_part)
node = field(2, b"merged_constant") + field(4, b"Constant") + field(5, attribute)
with open(sys.argv[1], "rb") as f:
    model = f.read()
with open(sys.argv[2], "wb") as f:  # a second occurrence of the model's graph: merged into the first
    f.write(model + field(7, field(1, node)))
PY
expect_exit 1 "whenet_fast.onnx with a tensor given twice" "$estimator" --dataset ds --predictions p.csv --model whenet \
  --models-dir m_merged
said "cannot load model file m_merged/whenet_fast.onnx: tensor"

echo "== 3. OpenCV's variables parsed as it loads: a bad value is a clear error and exit 2, never an abort"
for setting in OPENCV_IO_MAX_IMAGE_WIDTH=abc OPENCV_IO_MAX_IMAGE_HEIGHT= OPENCV_IO_MAX_IMAGE_PARAMS=-1 \
  OPENCV_IO_MAX_IMAGE_WIDTH=100000000000000000000 OPENCV_IO_MAX_IMAGE_WIDTH=5GB OPENCV_BUFFER_AREA_ALWAYS_SAFE=abc \
  OPENCV_DUMP_ERRORS=yes OPENCV_THREAD_POOL_ACTIVE_WAIT_WORKER=-3 OPENCV_VIDEOIO_DEBUG=on; do
  name=${setting%%=*}
  for program in "$estimator" "$annotate"; do
    expect_exit 0 "$setting $(basename "$program") --version" env "$setting" "$program" --version
    expect_exit 0 "$setting $(basename "$program") --help" env "$setting" "$program" --help
  done
  expect_exit 2 "$setting hkf-estimator" env "$setting" "$estimator" --dataset ds --predictions p.csv --second-model none
  said "hkf-estimator: $name='"
  expect_exit 2 "$setting hkf-annotate" env "$setting" "$annotate" clip.mp4 raw.lcmlog filtered.lcmlog a.mp4
  said "hkf-annotate: $name='"
done
# good values still load and run
expect_exit 0 "OPENCV_IO_MAX_IMAGE_WIDTH=5MB OPENCV_DUMP_ERRORS=false" env OPENCV_IO_MAX_IMAGE_WIDTH=5MB \
  OPENCV_DUMP_ERRORS=false "$estimator" --dataset ds --predictions p.csv --second-model none

echo "== 10. OPENCV_TRACE on would write OpenCVTrace.txt into the current folder, unchecked: refused"
expect_exit 2 "OPENCV_TRACE=1 hkf-estimator" env OPENCV_TRACE=1 "$estimator" --dataset ds --predictions p.csv --second-model none
said "OPENCV_TRACE='1' would have OpenCV write OpenCVTrace.txt"
[ ! -e OpenCVTrace.txt ] || fail "OpenCVTrace.txt was written"
expect_exit 0 "OPENCV_TRACE=0 hkf-estimator" env OPENCV_TRACE=0 "$estimator" --dataset ds --predictions p.csv --second-model none
[ ! -e OpenCVTrace.txt ] || fail "OpenCVTrace.txt was written"
echo "== 2. hkf-track never opens a log over a file its programs read: the config, the models (noted before any log)"
track=$build/tools/hkf-track
cp "$source/filter_node/hkf-filter.conf" my.conf
config_sum=$(sha256sum my.conf)
mkdir logs
ln my.conf logs/hkf-filter.log
expect_exit 1 "a log hard-linked to --config" "$track" --source "$data/videos/d3.mp4" --config my.conf --logs logs
said "'logs/hkf-filter.log' is the same file as 'my.conf'"
said "nothing started"
[ "$(sha256sum my.conf)" = "$config_sum" ] || fail "the config was changed"
pgrep -f "hkf-estimator --source $data/videos/d3.mp4" >/dev/null && fail "a program was started"
rm logs/hkf-filter.log
mkdir m_copy
cp "$models"/*.onnx "$models"/canonical_face.txt m_copy/
model_sum=$(sha256sum m_copy/whenet_fast.onnx)
ln -s "$work/m_copy/whenet_fast.onnx" logs/hkf-estimator.log
expect_exit 1 "a log symlinked to a model in HKF_MODELS_DIR" env HKF_MODELS_DIR="$work/m_copy" "$track" \
  --source "$data/videos/d3.mp4" --logs logs
said "is the same file as '$work/m_copy/whenet_fast.onnx'"
[ "$(sha256sum m_copy/whenet_fast.onnx)" = "$model_sum" ] || fail "the model was changed"
rm logs/hkf-estimator.log

echo "== 5. Ctrl-C in hkf-track's first 0.7 s: a program stopped before its first line lost no output"
for delay in 0.2 0.4 0.6; do
  "$track" --source "$data/videos/d3.mp4" --second-model none --logs logs >early.txt 2>&1 &
  running=$!
  sleep "$delay"
  kill -INT "$running"
  status=0
  wait "$running" || status=$?
  if grep -q "output was lost" early.txt || [ "$status" != 0 ]; then cat early.txt >&2; fail "Ctrl-C after $delay s: exit $status"; fi
  echo "Ctrl-C after $delay s: exit 0; $(grep -c "stopped before it wrote" early.txt || true) program(s) stopped before their first line"
done
# the estimator alone, Ctrl-C as it loads and warms up: a stop asked for is exit 0 with its summary, even
# before the first frame (it was exit 1, "no frame"); before its handler is set, the signal's own 130
stopped_early=0
for delay in 0.15 0.3 0.45 0.6 0.8; do
  "$estimator" --source "$data/videos/d3.mp4" --second-model none --lcm-url memq:// >early.txt 2>&1 &
  running=$!
  sleep "$delay"
  kill -INT "$running"
  status=0
  wait "$running" || status=$?
  case "$status" in
    0) grep -q "^hkf-estimator: [0-9]* frames," early.txt || fail "hkf-estimator Ctrl-C after $delay s: no summary"
       ! grep -q "^hkf-estimator: 0 frames," early.txt || stopped_early=$((stopped_early + 1)) ;;
    130) ;;
    *) cat early.txt >&2; fail "hkf-estimator Ctrl-C after $delay s: exit $status" ;;
  esac
done
echo "hkf-estimator, Ctrl-C at 5 times in its first 0.8 s: exit 0 or the signal's 130, never 1 ($stopped_early stopped before the first frame, exit 0)"
echo "== 4. (hkf.track.exclusive) a port LCM reads as 7667 is one claim however it is spelled"

echo "== 6. a port hkf-track passes on is read as its bridge reads it: refused before anything starts"
for option in "--flightgear 5550.0" "--flightgear 0x15ae" "--flightgear 5550e0" "--opentrack --opentrack-port 4242.0" \
  "--opentrack --opentrack-port +4242"; do
  # shellcheck disable=SC2086
  expect_exit 2 "hkf-track $option" "$track" --source "$data/videos/d3.mp4" $option --logs logs
  said "a UDP port from 1 to 65535 (digits alone)"
  if grep -q "started" "$work/out.txt"; then fail "hkf-track $option started a program"; fi
done
expect_exit 2 "hkf-opentrack --port 4242.0" "$build/tools/hkf-opentrack" --port 4242.0
said "wants a UDP port from 1 to 65535"

echo "== 8. a UTF-8 byte order mark at a config file's start is no part of its first key"
printf '\xef\xbb\xbfstillness = 2\n' >bom.conf
expect_exit 0 "a config with a BOM" "$build/tools/hkf-filter" --config bom.conf --print-config
said "^stillness  *= 2 .*bom.conf:1"

echo "== 9. the status channel is none of the node's other channels"
for channel in HEAD_POSE HEAD_POSE_RAW HEAD_TRACKER_CMD; do
  expect_exit 2 "--status-channel $channel" "$build/tools/hkf-filter" --status-channel "$channel" --lcm-url memq://
  said "both '$channel': each of the node's channels has one use"
done
expect_exit 2 "--output-channel HEAD_POSE_RAW" "$build/tools/hkf-filter" --output-channel HEAD_POSE_RAW --lcm-url memq://
echo "== review: outputs named through /dev/fd and /proc/self/fd, a bind mount, a full tmpfs"
filter=$build/tools/hkf-filter
"$estimator" --source "$data/videos/d3.mp4" --max-frames 30 --second-model none --lcm-url "file://$work/raw.lcmlog?mode=w" \
  >/dev/null 2>&1 || fail "the raw log"
raw_sum=$(sha256sum raw.lcmlog)
expect_exit 1 "--offline to /dev/fd/5, the input open there" "$filter" --offline raw.lcmlog /dev/fd/5 5<>raw.lcmlog
said "'/dev/fd/5' is also 'raw.lcmlog'"
expect_exit 1 "--offline to /proc/self/fd/5" "$filter" --offline raw.lcmlog /proc/self/fd/5 5<>raw.lcmlog
said "'/proc/self/fd/5' is also 'raw.lcmlog'"
if [ "$(id -u)" = 0 ] && unshare -m true 2>/dev/null; then
  touch bound.lcmlog
  expect_exit 1 "--offline to a bind mount of the input" unshare -m sh -c \
    "mount --bind raw.lcmlog bound.lcmlog && exec '$filter' --offline raw.lcmlog bound.lcmlog"
  said "'bound.lcmlog' is also 'raw.lcmlog'"
  mkdir small
  expect_exit 1 "--offline and --csv onto a full tmpfs" unshare -m sh -c \
    "mount -t tmpfs -o size=8k tmpfs small && exec '$filter' --offline raw.lcmlog small/out.lcmlog --csv small/out.csv"
  said "error writing 'small/out.lcmlog' (a full disk?)"
else
  echo "(not root, or no mount namespace: the bind mount and the full tmpfs not tried)"
fi
[ "$(sha256sum raw.lcmlog)" = "$raw_sum" ] || fail "the raw log was changed"
echo "== review: a model whose Reshape, Expand, Tile or ConstantOfShape asks for 2^48 elements (each size within the"
echo "   check's 2^24): OpenCV refuses it while importing (an allocation it cannot make, or its own assertion); exit 1"
for op in ConstantOfShape Reshape Expand Tile; do
  mkdir "m_$op"
  cp "$models"/*.onnx "$models"/canonical_face.txt "m_$op/"
  "$python" - "$op" "m_$op/whenet_fast.onnx" <<'PY'
import sys
import numpy as np
import onnx
from onnx import TensorProto, helper
op, path = sys.argv[1], sys.argv[2]
big = 1 << 24
shape = [big, big] if op == "ConstantOfShape" else [big, big, 1, 1]
nodes = [helper.make_node("Constant", [], ["s"], value=helper.make_tensor("sv", TensorProto.INT64, [len(shape)],
                                                                           np.array(shape, np.int64).tobytes(), raw=True))]
nodes += [helper.make_node("ConstantOfShape", ["s"], ["c"]), helper.make_node("Add", ["x", "c"], ["y"])] \
    if op == "ConstantOfShape" else [helper.make_node(op, ["x", "s"], ["y"])]
graph = helper.make_graph(nodes, op, [helper.make_tensor_value_info("x", TensorProto.FLOAT, [1, 3, 224, 224])],
                          [helper.make_tensor_value_info("y", TensorProto.FLOAT, [1])])
onnx.save(helper.make_model(graph, opset_imports=[helper.make_opsetid("", 13)]), path)
PY
  # under AddressSanitizer a malloc beyond its largest size aborts by its own policy; a release build's malloc
  # returns NULL there, which OpenCV turns into its error: the same asked of ASan
  expect_exit 1 "whenet_fast.onnx asking $op for 2^48 elements" env \
    ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}allocator_may_return_null=1" "$estimator" --dataset ds \
    --predictions p.csv --model whenet --models-dir "m_$op"
  said "cannot load model file m_$op/whenet_fast.onnx"
done
echo "faults_round6_test: all checks passed"
