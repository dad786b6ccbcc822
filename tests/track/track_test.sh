#!/usr/bin/env bash
# hkf-track, the one-command live tracker, end to end over udpm in a private
# network namespace: a real face video stands in for the camera (--realtime),
# the estimator, filter and opentrack bridge run, a stand-in for opentrack's UDP
# input receives. Then Ctrl-C (SIGINT to the launcher): every program must be
# gone, and the receiver must hold exactly the bytes for the poses published.
# Also: a video that ends stops everything by itself; a missing source is a
# clear error. Needs root (unshare --net); exits 77 (skipped) otherwise.
# usage: track_test.sh BUILD_DIR SOURCE_DIR PYTHON VIDEO_DIR
set -euo pipefail
trap 'echo "track_test: line $LINENO failed" >&2' ERR
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd) python=$3 videos=$4

if [ "${HKF_IN_NETNS:-}" != 1 ]; then
  HKF_IN_NETNS=1 exec "$source/tools/lcm-netns" "$0" "$@"
fi
url="udpm://239.255.76.67:7667?ttl=0"
track=("$build/tools/hkf-track")  # the build tree's, finding its programs from its own place
work=$(mktemp -d)
pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; rm -rf "$work"; }
trap cleanup EXIT
fail() { echo "FAIL: $*" >&2; cat "$work/track.txt" >&2 2>/dev/null || true; exit 1; }

"$python" "$source/tests/opentrack/udp_receiver.py" "$work/udp.hex" --port 4242 2>"$work/receiver.txt" &
pids+=($!)
. "$source/tests/lib/wait_until.sh"
wait_until 60 "the UDP receiver" test -e "$work/udp.hex.ready" || fail "the UDP receiver did not start"
lcm-logger -q -f -c HEAD_POSE --lcm-url "$url" "$work/poses.lcmlog" &
logger_pid=$!
pids+=("$logger_pid")

"${track[@]}" --source "$videos/d3.mp4" --realtime --opentrack --logs "$work/logs" >"$work/track.txt" 2>&1 &
track_pid=$!
# Ctrl-C once 150 poses have reached the receiver and 5 status lines are shown (90 s at most)
enough() { [ "$(wc -l <"$work/udp.hex")" -ge 150 ] && [ "$(grep -c "poses/s" "$work/track.txt")" -ge 5 ]; }
wait_until 90 "150 datagrams and 5 status lines" enough || fail "hkf-track did not deliver poses"
kill -INT "$track_pid"                           # Ctrl-C
wait "$track_pid" || fail "hkf-track did not exit cleanly on Ctrl-C"
cat "$work/track.txt"
sleep 0.3
kill -INT "$logger_pid"; wait "$logger_pid" || true

started=$(sed -n 's/^hkf-track: started \(hkf-[a-z]*\) (pid \([0-9]*\)).*/\1 \2/p' "$work/track.txt")
[ "$(echo "$started" | wc -l)" = 3 ] || fail "expected 3 programs started"
while read -r name pid; do
  if kill -0 "$pid" 2>/dev/null; then fail "$name (pid $pid) still runs after Ctrl-C"; fi
done <<<"$started"
lines=$(grep -c "camera .* fps .* poses/s,.* capture->pose p50" "$work/track.txt" || true)
[ "$lines" -ge 4 ] || fail "expected a status line a second, got $lines"
grep -q "hkf-opentrack: [1-9][0-9]* poses received" "$work/track.txt" || fail "no bridge summary"
grep -q "hkf-estimator: [1-9][0-9]* frames" "$work/track.txt" || fail "no estimator summary"
"$python" "$source/tests/opentrack/check_datagrams.py" --types "$build/lcmtypes/python" \
  "$work/poses.lcmlog" "$work/udp.hex" || fail "the datagrams are not the published poses"
received=$(wc -l <"$work/udp.hex")
[ "$received" -ge 100 ] || fail "only $received poses reached the UDP receiver in ~5 s of 30 fps video"

# a source that ends: everything stops by itself, exit 0
"${track[@]}" --source "$videos/d18.mp4" --logs "$work/logs2" >"$work/end.txt" 2>&1 || fail "exit status at the end of the source"
grep -q "the source ended" "$work/end.txt" || fail "no end-of-source message"
# ... read faster than real time, its stamps are the file's time: the status line gives no latency
if grep -q "capture->pose" "$work/end.txt"; then fail "a latency shown for a file read faster than real time"; fi
grep -q "no latency (a file faster than real time" "$work/end.txt" || fail "the status line does not say why no latency"
# logs on a full disk (a file-size limit of 0 for the tracker and its programs): exit 1, said
{ (ulimit -f 0; exec "${track[@]}" --source "$videos/d18.mp4" --logs "$work/logs3") 2>&1 && echo "exit 0" ||
  echo "exit $?"; } | cat >"$work/full.txt"
grep -q "its output was lost (a full disk?)" "$work/full.txt" || fail "logs on a full disk: not reported"
grep -qx "exit 1" "$work/full.txt" || fail "logs on a full disk: $(tail -n 1 "$work/full.txt") (expected exit 1)"
# bad input: a clear message and a non-zero exit
if "${track[@]}" --source "$work/missing.mp4" 2>"$work/bad.txt"; then fail "a missing source was accepted"; fi
grep -q "no such file" "$work/bad.txt" || fail "no clear message for a missing source"
# bad_args EXPECTED_TEXT ARGS...: a clear message and exit 2, nothing started
bad_args() {
  local text=$1 status=0
  shift
  "${track[@]}" "$@" >"$work/args.txt" 2>&1 || status=$?
  [ "$status" = 2 ] || fail "hkf-track $*: exit $status, not 2"
  grep -q -- "$text" "$work/args.txt" || fail "hkf-track $*: no '$text' in: $(cat "$work/args.txt")"
  if grep -q "started" "$work/args.txt"; then fail "hkf-track $*: a program was started"; fi
}
clip=$videos/d18.mp4
bad_args "give one of --camera N and --source FILE" --camera 0 --source "$clip"
bad_args "give one of --camera N and --source FILE" --realtime
bad_args "unknown option --nonsense" --source "$clip" --nonsense
bad_args "--rate wants a frequency from 0.1" --source "$clip" --rate 0
bad_args "--rate wants a frequency from 0.1" --source "$clip" --rate 0.05
bad_args "--opentrack-port wants a UDP port from 1 to 65535" --source "$clip" --opentrack --opentrack-port 99999
bad_args "memq:// stays inside one process" --source "$clip" --lcm-url memq://
bad_args "--seconds wants a duration >= 0" --source "$clip" --seconds -1
bad_args "--detector wants retina, short or full" --source "$clip" --detector wide
bad_args "a file:// log is for hkf-estimator" --source "$clip" --lcm-url "file://$work/x.lcmlog"
bad_args "an open quote" --source "$clip" --opentrack --opentrack-args "--invert 'yaw"
bad_args "is missing" --source "$clip" --build "$work/no-build"
# a child that refuses what hkf-track passed on: its exit 2 is hkf-track's
status=0
"${track[@]}" --source "$clip" --logs "$work/logs_bad" --opentrack --opentrack-args "--lead 1e9" >"$work/child.txt" 2>&1 || status=$?
[ "$status" = 2 ] || fail "a child's bad arguments: hkf-track exit $status, not 2: $(cat "$work/child.txt")"
# two trackers: the second on the same LCM URL, or the same log folder, is refused and starts nothing
"${track[@]}" --source "$videos/d3.mp4" --realtime --logs "$work/logs_first" >"$work/first.txt" 2>&1 &
first_pid=$!
pids+=("$first_pid")
wait_until 60 "the first tracker's start" has_line "$work/first.txt" "Ctrl-C stops" || fail "the first tracker did not start"
bad_args "another hkf-track runs on this LCM URL" --source "$clip" --logs "$work/logs_second"
bad_args "another hkf-track writes its logs in this folder" --source "$clip" --logs "$work/logs_first" \
  --lcm-url "udpm://239.255.76.67:7668?ttl=0"
wait_until 60 "a status line from the first tracker" has_line "$work/first.txt" "poses/s" || fail "no status line"
kill -INT "$first_pid"
wait "$first_pid" || fail "the first tracker did not stop cleanly"
grep -q "poses/s" "$work/first.txt" || fail "the first tracker showed no status line"
# hkf-track killed between a child's fork and its request for the parent-death signal (a shim makes the
# request 0.5 s late): the child sees its parent gone and ends, never running on as an orphan
cp "$videos/d3.mp4" "$work/orphan_clip.mp4"
LD_PRELOAD="$build/tests/libhkf_test_slow_pdeathsig.so" "${track[@]}" --source "$work/orphan_clip.mp4" --realtime \
  --logs "$work/logs_orphan" >"$work/orphan.txt" 2>&1 &
orphan_track=$!
for _ in $(seq 100); do grep -q "started hkf-estimator" "$work/orphan.txt" && break; sleep 0.05; done
kill -9 "$orphan_track"
wait "$orphan_track" 2>/dev/null || true
# the child (hkf-track's own command line until it runs a program) is gone once it has checked; an orphan
# would run the clip for 12 s
for _ in $(seq 80); do pgrep -f "$work/orphan_clip.mp4" >/dev/null || break; sleep 0.1; done
if pgrep -f "$work/orphan_clip.mp4" >/dev/null; then
  pkill -f "$work/orphan_clip.mp4" || true
  fail "a child of hkf-track ran on after hkf-track was killed before its parent-death signal was set"
fi
echo "hkf-track killed before its child asked for the parent-death signal: no orphan"
"${track[@]}" --help | grep -q "^usage: hkf-track" || fail "--help"
echo "track_test: passed ($received poses reached the UDP receiver; programs stopped on Ctrl-C)"
