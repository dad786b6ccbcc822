#!/usr/bin/env bash
# hkf-opentrack end to end over real UDP, in a private network namespace (no
# traffic leaves this machine): lcm-logplayer replays a drive, hkf-filter runs
# live, several hkf-opentrack bridges send to stand-ins for opentrack's UDP
# input, lcm-logger records HEAD_POSE. Each receiver must hold exactly the
# bytes opentrack expects for the recorded poses, message for message. Bad
# input: a NaN pose, a destination nobody listens on, a local port in use. A bridge in --flightgear mode
# sends FlightGear's lines, each checked the same way.
# Needs root (unshare --net); exits 77 (skipped) otherwise.
# usage: opentrack_netns_test.sh BUILD_DIR SOURCE_DIR PYTHON
set -euo pipefail
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd) python=$3

if [ "${HKF_IN_NETNS:-}" != 1 ]; then
  HKF_IN_NETNS=1 exec "$source/tools/lcm-netns" "$0" "$@"
fi
url="udpm://239.255.76.67:7667?ttl=0"
types="$build/lcmtypes/python"
here="$source/tests/opentrack"
work=$(mktemp -d)
pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; rm -rf "$work"; }
trap cleanup EXIT
fail() { echo "FAIL: $*" >&2; tail -n 5 "$work"/*.txt >&2 2>/dev/null || true; exit 1; }

"$build/tools/hkf-simlog" --out "$work/raw.lcmlog" --seconds 10 --seed 7 >/dev/null

# receivers standing in for opentrack
for port in 4242 4243 4245 5550; do
  "$python" "$here/udp_receiver.py" "$work/udp$port.hex" --port "$port" 2>"$work/receiver$port.txt" &
  pids+=($!)
done
for port in 4242 4243 4245 5550; do
  for _ in $(seq 50); do [ -e "$work/udp$port.hex.ready" ] && break; sleep 0.1; done
  [ -e "$work/udp$port.hex.ready" ] || fail "receiver on $port did not start"
done

lcm-logger -q -f -c HEAD_POSE --lcm-url "$url" "$work/poses.lcmlog" &
logger_pid=$!
pids+=("$logger_pid")
# no rest asked for (rest_time 0): the centre moves at the RECENTER alone (a rest would move it onto its mean
# when measured: hkf.filter_node.node_rest)
"$build/tools/hkf-filter" --lcm-url "$url" --set rest_time=0 2>"$work/filter.txt" &
filter_pid=$!
pids+=("$filter_pid")

# bridge NAME [options]: one hkf-opentrack; its summary goes to NAME.txt
bridges=()
bridge() {
  local name=$1
  shift
  "$build/tools/hkf-opentrack" --lcm-url "$url" "$@" 2>"$work/$name.txt" &
  pids+=($!)
  bridges+=($!)
}
bridge defaults                                  # relative to the centre, hold while LOST
bridge options --port 4243 --absolute --lost send --invert yaw --scale pitch=2 --scale roll=-0.5
bridge nobody --port 4244                        # nothing listens there
bridge rate --port 4245 --rate 50
bridge flightgear --flightgear --eye -0.21,0.208,0.36 --invert yaw   # FlightGear's generic input (port 5550)
sleep 0.7

lcm-logplayer -s 2 --lcm-url "$url" "$work/raw.lcmlog" &
player_pid=$!
sleep 2.5
"$build/tools/hkf-cmd" recenter --lcm-url "$url" || fail "hkf-cmd recenter"   # mid-drive, as a hotkey would
wait "$player_pid"
sleep 0.3
# a hostile pose: NaN pitch, published where the bridges listen
"$python" - "$types" "$url" <<'PY'
import sys
import lcm
sys.path.insert(0, sys.argv[1])
from hkf import head_pose_t
m = head_pose_t()
m.status = head_pose_t.TRACKING
m.pitch = float("nan")
lcm.LCM(sys.argv[2]).publish("HEAD_POSE", m.encode())
PY
sleep 0.2  # the NaN pose has reached the bridges; what --rate sends from here on is counted
rate_before_nan=$(wc -l <"$work/udp4245.hex")
sleep 0.5
rate_after_nan=$(wc -l <"$work/udp4245.hex")

for p in "${bridges[@]}"; do
  kill -INT "$p"
  wait "$p" || fail "hkf-opentrack did not exit cleanly on SIGINT"
done
kill -INT "$filter_pid" "$logger_pid"
wait "$filter_pid" || fail "hkf-filter did not exit cleanly"
wait "$logger_pid" || true
sleep 0.2
for p in "${pids[@]}"; do kill -TERM "$p" 2>/dev/null || true; done
wait || true
cat "$work/filter.txt" "$work"/defaults.txt "$work"/options.txt "$work"/nobody.txt "$work"/rate.txt "$work"/flightgear.txt
grep -q "300 measurements" "$work/filter.txt" || fail "the live filter did not receive all 300 measurements"

check() { "$python" "$here/check_datagrams.py" --types "$types" "$work/poses.lcmlog" "$@"; }
check "$work/udp4242.hex" || fail "defaults: the bytes differ"
check "$work/udp4243.hex" --absolute --lost send --invert yaw --scale pitch=2 --scale roll=-0.5 \
  || fail "options: the bytes differ"
check "$work/udp4245.hex" --rate || fail "--rate: datagrams that were not due"
check "$work/udp5550.hex" --flightgear=-0.21,0.208,0.36 --invert yaw || fail "--flightgear: the lines differ"
grep -q "sent to FlightGear at 127.0.0.1 port 5550" "$work/flightgear.txt" || fail "--flightgear's summary"
grep -q "1 commands" "$work/filter.txt" || fail "hkf-filter did not get the RECENTER"
# the centre moved once, mid-drive, onto the pose of that moment
"$python" - "$types" "$work/poses.lcmlog" <<'PY' || fail "RECENTER did not move the published centre"
import sys
import lcm
sys.path.insert(0, sys.argv[1])
from hkf import head_pose_t
poses = [head_pose_t.decode(e.data) for e in lcm.EventLog(sys.argv[2], "r") if e.channel == "HEAD_POSE"]
poses = [p for p in poses if p.seq > 0]
changes = [i for i in range(1, len(poses)) if list(poses[i].center) != list(poses[i - 1].center)]
assert len(changes) == 1 and 30 < changes[0] < 270, changes
before, after = poses[changes[0] - 1], poses[changes[0]]
assert list(after.center) == [before.pitch, before.yaw, before.roll], (after.center, before)
print(f"recenter: the centre moved at pose {changes[0]} onto {[round(c, 2) for c in after.center]}")
PY
grep -q "302 poses received" "$work/defaults.txt" || fail "the bridge did not receive the 300 poses, the NaN one and the LOST one after the replay"
# every LOST pose is the last pose held: those in the drive, and 1 when the replay ended (the estimator fell silent)
lost=$("$python" - "$types" "$work/poses.lcmlog" <<'PY'
import sys
import lcm
sys.path.insert(0, sys.argv[1])
from hkf import head_pose_t
print(sum(head_pose_t.decode(e.data).status == head_pose_t.LOST for e in lcm.EventLog(sys.argv[2], "r") if e.channel == "HEAD_POSE"))
PY
)
[ "$lost" -ge 2 ] || fail "the drive should lose the face at least once (and at its end): $lost LOST poses"
grep -q "$lost repeats of the last pose while LOST" "$work/defaults.txt" || fail "expected $lost LOST poses held"
grep -q "1 non-finite" "$work/defaults.txt" || fail "the NaN pose was not counted as dropped"
grep -q "Connection refused" "$work/nobody.txt" || fail "no clear message for a destination nobody listens on"
grep -Eq "[1-9][0-9]* send errors" "$work/nobody.txt" || fail "refused sends not counted"
# round 4: after a pose it could not send, --rate sends nothing (it repeated the last packet silently)
[ $((rate_after_nan - rate_before_nan)) -le 1 ] ||
  fail "--rate went on with the last packet after a dropped pose: $((rate_after_nan - rate_before_nan)) datagrams in 0.5 s"
rate_count=$(wc -l <"$work/udp4245.hex")
[ "$rate_count" -ge 150 ] || fail "--rate 50 sent only $rate_count datagrams in ~6 s"

# a local port in use: a clear message and exit 1
"$python" -c "
import socket, subprocess, sys
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM); s.bind(('0.0.0.0', 5555))
r = subprocess.run(['$build/tools/hkf-opentrack', '--bind', '5555'], capture_output=True, text=True, timeout=10)
sys.stderr.write(r.stderr)
sys.exit(0 if r.returncode == 1 and 'in use' in r.stderr else 1)" || fail "--bind to a port in use"
echo "opentrack_netns_test: passed ($rate_count datagrams at 50 Hz)"
