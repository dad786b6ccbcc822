#!/usr/bin/env bash
# The Python side from nothing but pip: a fresh venv gets the README's
# `pip install ./lcmtypes/python` (which brings PyPI's lcm), then
# tools/examples/head_pose_subscriber.py runs against a replayed drive
# (lcm-logplayer -> live hkf-filter, in a private network namespace) and must
# print the poses hkf-filter --offline computes for the same log.
# Needs root (unshare --net) for the replay; exits 77 (skipped) otherwise.
# usage: subscriber_test.sh BUILD_DIR SOURCE_DIR PYTHON
set -euo pipefail
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd) python=$3
fail() { echo "FAIL: $*" >&2; exit 1; }

if [ "${HKF_IN_NETNS:-}" != 1 ]; then
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  # exactly the README's steps (with the network, before the private namespace)
  python3 -m venv "$work/venv"
  "$work/venv/bin/pip" install -q --disable-pip-version-check "$source/lcmtypes/python" || fail "pip install ./lcmtypes/python"
  status=0
  HKF_IN_NETNS=1 HKF_WORK=$work "$source/tools/lcm-netns" "$0" "$@" || status=$?
  exit $status
fi
work=$HKF_WORK
url="udpm://239.255.76.67:7667?ttl=0"
"$build/tools/hkf-simlog" --out "$work/raw.lcmlog" --seconds 10 --seed 4 >/dev/null
"$build/tools/hkf-filter" --offline "$work/raw.lcmlog" "$work/expected.lcmlog" 2>/dev/null

"$build/tools/hkf-filter" --lcm-url "$url" 2>"$work/filter.txt" &
filter_pid=$!
"$work/venv/bin/python" "$source/tools/examples/head_pose_subscriber.py" --lcm-url "$url" --count 300 --timeout 10 \
  >"$work/printed.txt" 2>"$work/subscriber.txt" &
subscriber_pid=$!
# both listening before the log is played (their start-up lines), however long Python takes to start
. "$source/tests/lib/wait_until.sh"
wait_until 60 "start-up line from hkf-filter" has_line "$work/filter.txt" "^hkf-filter: .* -> .* on " || fail "hkf-filter did not start"
wait_until 60 "start-up line from the subscriber" has_line "$work/subscriber.txt" "listening on HEAD_POSE" ||
  fail "the subscriber did not start"
lcm-logplayer -s 2 --lcm-url "$url" "$work/raw.lcmlog"
wait "$subscriber_pid" || { cat "$work/subscriber.txt" >&2; kill "$filter_pid"; fail "the subscriber did not get 300 poses"; }
kill -INT "$filter_pid"
wait "$filter_pid" || true
cat "$work/subscriber.txt"
head -n 3 "$work/printed.txt"

# the printed poses against the offline filter's, seq for seq
"$python" - "$work/expected.lcmlog" "$work/printed.txt" "$build/lcmtypes/python" <<'PY'
import math
import re
import sys

import lcm

sys.path.insert(0, sys.argv[3])
from hkf import head_pose_t

names = {1: "TRACKING", 2: "COASTING", 3: "LOST"}
expected = {}
for e in lcm.EventLog(sys.argv[1], "r"):
    if e.channel != "HEAD_POSE":
        continue  # the status beside each pose (HEAD_POSE_STATUS)
    p = head_pose_t.decode(e.data)
    yaw = math.fmod(p.yaw - p.center[1] + 540.0, 360.0) - 180.0
    expected[p.seq] = (names[p.status], p.pitch - p.center[0], yaw, p.roll - p.center[2])
lines = open(sys.argv[2]).read().split("\n")[:-1]
pattern = re.compile(r"seq=(\d+) (\w+) pitch=(\S+) yaw=(\S+) roll=(\S+)$")
for line in lines:
    m = pattern.match(line)
    assert m, f"unexpected line {line!r}"
    status, *angles = expected[int(m.group(1))]
    assert m.group(2) == status, line
    for got, want in zip(map(float, m.group(3, 4, 5)), angles):
        assert abs(got - want) <= 6e-4, f"{line}: {got} != {want:.4f}"
# the offline log also ends with the LOST pose of the silence after it; the subscriber stopped at 300
assert len(lines) == 300 and len(expected) == 301 and expected[max(expected)][0] == "LOST", (len(lines), len(expected))
print(f"subscriber_test: {len(lines)} printed poses match the offline filter")
PY
