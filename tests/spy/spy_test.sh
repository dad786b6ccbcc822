#!/usr/bin/env bash
# hkf-spy puts lcm.jar and the hkf types jar on lcm-spy's class path, and the
# class lcm-spy starts and the hkf types are found there.
# usage: spy_test.sh BUILD_DIR
set -euo pipefail
spy=$1/tools/hkf-spy
grep -q "usage: hkf-spy" <<<"$("$spy" --help)"
cp=$("$spy" --print-class-path)
echo "class path: $cp"
IFS=: read -r -a jars <<<"$cp"
for jar in "${jars[@]}"; do [ -f "$jar" ] || { echo "FAIL: $jar missing" >&2; exit 1; }; done
listing=$(for jar in "${jars[@]}"; do unzip -l "$jar"; done)
for class in lcm/spy/Spy.class hkf/head_pose_t.class hkf/head_pose_measurement_t.class hkf/tracker_command_t.class; do
  grep -q "$class" <<<"$listing" || { echo "FAIL: $class not on the class path" >&2; exit 1; }
done
echo "spy_test: class path checked"

# lcm-spy itself, started by hkf-spy under a virtual display in a private
# network namespace, must find the five hkf types (hkf 0.1's two too, for its logs).
if [ "$(id -u)" = 0 ] && command -v Xvfb >/dev/null && unshare --net true 2>/dev/null; then
  out=$(mktemp)
  # each step waits for what it needs (the display's socket, lcm-spy's line), 60 s at most
  "$(dirname "$0")/../../tools/lcm-netns" bash -c '
    . "$3"
    rm -f /tmp/.X11-unix/X97
    Xvfb :97 -screen 0 1024x768x24 >/dev/null 2>&1 & xvfb=$!
    wait_until 60 "Xvfb display :97" test -S /tmp/.X11-unix/X97
    DISPLAY=:97 "$1" --lcm-url "udpm://239.255.76.67:7667?ttl=0" >"$2" 2>&1 & spy=$!
    wait_until 60 "the types found by lcm-spy" has_line "$2" "Found [0-9]+ LCM types"
    kill $spy $xvfb 2>/dev/null; wait 2>/dev/null' _ "$spy" "$out" "$(dirname "$0")/../lib/wait_until.sh" || true
  cat "$out"
  grep -q "Found 10 LCM types" "$out" || { echo "FAIL: lcm-spy did not find the 10 hkf types (7, hkf 0.1's two and 0.2's pose)" >&2; rm -f "$out"; exit 1; }
  rm -f "$out"
else
  echo "(lcm-spy start-up not checked: needs root, unshare and Xvfb)"
fi
echo "spy_test: lcm-spy check done"
