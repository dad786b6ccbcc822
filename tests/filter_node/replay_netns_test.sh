#!/usr/bin/env bash
# The real LCM tools end to end, in a private network namespace (no traffic
# leaves this machine): lcm-logplayer replays a measurement log, hkf-filter
# runs live, lcm-logger records HEAD_POSE. The recording must equal
# hkf-filter --offline's output (count and values), and the Java types must
# decode it. Needs root (unshare --net); exits 77 (skipped) otherwise.
# usage: replay_netns_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd)

if [ "${HKF_IN_NETNS:-}" != 1 ]; then
  HKF_IN_NETNS=1 exec "$source/tools/lcm-netns" "$0" "$@"
fi
url="udpm://239.255.76.67:7667?ttl=0"
work=$(mktemp -d)
pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; rm -rf "$work"; }
trap cleanup EXIT
fail() { echo "FAIL: $*" >&2; cat "$work"/*.txt >&2 2>/dev/null || true; exit 1; }

"$build/tools/hkf-simlog" --out "$work/raw.lcmlog" --seconds 10 --seed 3
"$build/tools/hkf-filter" --offline "$work/raw.lcmlog" "$work/expected.lcmlog" 2>"$work/offline.txt"

# live_run NAME SPEED SIGNAL [hkf-filter options]: hkf-filter live while
# lcm-logplayer replays the raw log, then SIGNAL; its summary goes to NAME.txt.
live_run() {
  local name=$1 speed=$2 signal=$3
  shift 3
  "$build/tools/hkf-filter" --lcm-url "$url" "$@" 2>"$work/$name.txt" &
  local filter_pid=$!
  pids+=("$filter_pid")
  sleep 0.5
  lcm-logplayer -s "$speed" --lcm-url "$url" "$work/raw.lcmlog"
  sleep 0.5
  kill -"$signal" "$filter_pid"
  wait "$filter_pid" || fail "hkf-filter did not exit cleanly on SIG$signal"
  grep -q "poses published" "$work/$name.txt" || fail "no summary after SIG$signal"
  cat "$work/$name.txt"
}

lcm-logger -q -f -c HEAD_POSE --lcm-url "$url" "$work/recorded.lcmlog" &
logger_pid=$!
pids+=("$logger_pid")
live_run live 2 INT
sleep 0.3
kill -INT "$logger_pid"
wait "$logger_pid" || true
cat "$work/offline.txt"
grep -q "300 measurements" "$work/live.txt" || fail "the live filter did not receive all 300 measurements"

"$source/.venv/bin/python" "$source/dev/logs/compare_pose_logs.py" --types "$build/lcmtypes/python" \
  "$work/expected.lcmlog" "$work/recorded.lcmlog" || fail "recorded HEAD_POSE differs from the offline output"
"$source/tests/lcmtypes/java_decode_test.sh" "$build" "$source" "$work/recorded.lcmlog" || fail "Java decode"

# live --rate: extrapolated poses between the replayed measurements
live_run rate 4 TERM --rate 120
extrapolated=$(sed -n 's/.*(\([0-9]*\) extrapolated).*/\1/p' "$work/rate.txt")
[ "${extrapolated:-0}" -gt 100 ] || fail "expected extrapolated poses at 120 Hz, got ${extrapolated:-none}"
echo "replay_netns_test: passed"
