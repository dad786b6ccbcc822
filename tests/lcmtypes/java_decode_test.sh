#!/usr/bin/env bash
# The generated Java types decode HEAD_POSE messages of an LCM log exactly as
# the Python types do. usage: java_decode_test.sh BUILD_DIR SOURCE_DIR LOG
set -euo pipefail
build=$1 source=$2 log=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp="/usr/share/java/lcm.jar:$build/lcmtypes/hkf_lcmtypes.jar"
javac -nowarn -cp "$cp" -d "$work" "$source/tests/lcmtypes/DecodeHeadPoseLog.java"
java_says=$(java -cp "$cp:$work" DecodeHeadPoseLog "$log")
python_says=$("$source/.venv/bin/python" "$source/tests/lcmtypes/decode_head_pose_log.py" "$log" "$build/lcmtypes/python")
echo "java:   $java_says"
echo "python: $python_says"
[ "${java_says%% *}" -gt 0 ] || { echo "FAIL: no HEAD_POSE message decoded" >&2; exit 1; }
[ "$java_says" = "$python_says" ] || { echo "FAIL: Java and Python decode differently" >&2; exit 1; }
echo "java_decode_test: passed"
