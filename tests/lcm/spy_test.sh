#!/usr/bin/env bash
# hkf-spy puts lcm.jar and the hkf types jar on lcm-spy's class path, and the
# class lcm-spy starts and the hkf types are found there.
# usage: spy_test.sh BUILD_DIR
set -euo pipefail
spy=$1/tools/hkf-spy
"$spy" --help | grep -q "usage: hkf-spy"
cp=$("$spy" --print-class-path)
echo "class path: $cp"
IFS=: read -r -a jars <<<"$cp"
for jar in "${jars[@]}"; do [ -f "$jar" ] || { echo "FAIL: $jar missing" >&2; exit 1; }; done
listing=$(for jar in "${jars[@]}"; do unzip -l "$jar"; done)
for class in lcm/spy/Spy.class hkf/head_pose_t.class hkf/head_pose_measurement_t.class hkf/tracker_command_t.class; do
  grep -q "$class" <<<"$listing" || { echo "FAIL: $class not on the class path" >&2; exit 1; }
done
echo "spy_test: passed"
