#!/usr/bin/env bash
# The live view of a running tracker, end to end over udpm in a private network namespace: hkf-track --view
# plays a real face video as the camera; a client reads the page's event stream as a browser does (and that
# of an hkf-view started beside it, as for a tracker started otherwise: every kind of event). Checked:
# the raw and filtered poses, the rest's status and hkf-track's own line reach the page (the line the very
# text the terminal shows); camera pictures come at >= 10 fps within 200 ms of capture, a JPEG with the face;
# the page's recentre makes the node recentre (its command count and centre); the stillness knob changes the
# wander in use; saving writes the user's config file, which hkf-filter then reads.
# Needs root (unshare --net); exits 77 (skipped) otherwise.
# usage: view_live_test.sh BUILD_DIR SOURCE_DIR PYTHON VIDEO_DIR
set -euo pipefail
trap 'echo "view_live_test: line $LINENO failed" >&2' ERR
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd) python=$3 videos=$4
if [ "${HKF_IN_NETNS:-}" != 1 ]; then
  HKF_IN_NETNS=1 exec "$source/tools/lcm-netns" "$0" "$@"
fi
. "$source/tests/view/tracker_with_view.sh"
# hkf-view beside it, as for a tracker started otherwise: the same channels, its own line
"$build/tools/hkf-view" --listen "127.0.0.1:$((port + 1))" --seconds 60 >"$work/view.txt" 2>&1 &
view_pid=$!
start_tracker_with_view "$videos/d14.mp4"
"$python" "$source/tests/view/sse_client.py" "http://127.0.0.1:$((port + 1))" 60 "$work/beside.jsonl" "$work/beside.jpg" \
  --pictures 3 --line || fail "hkf-view beside the tracker"
kill -INT "$view_pid"
wait "$view_pid" || fail "hkf-view did not stop cleanly"
for kind in raw pose status line picture; do
  grep -q "\"t\": \"$kind\"" "$work/beside.jsonl" || fail "hkf-view beside the tracker sent no $kind event"
done
token=$(curl -s "$base/" | sed -n 's/.*name="hkf-token" content="\([0-9a-f]\{32\}\)".*/\1/p')
post() { curl -s -o /dev/null -w '%{http_code}' -X POST -H "X-HKF-Token: $token" "$base/command/$1"; }
"$python" "$source/tests/view/sse_client.py" "$base" 60 "$work/events1.jsonl" "$work/picture.jpg" --pictures 40 --line \
  --measured ||
  fail "the page's events"
[ "$(post recenter)" = 200 ] || fail "the page's recentre was refused"
[ "$(post 'stillness?value=3')" = 200 ] || fail "the stillness knob was refused"
[ "$(post save)" = 200 ] || fail "save was refused"
"$python" "$source/tests/view/sse_client.py" "$base" 60 "$work/events2.jsonl" "$work/picture2.jpg" --commands 3 --line ||
  fail "the commands' effect on the page"
stop_tracker
"$python" "$source/tests/view/check_live_events.py" "$work/events1.jsonl" "$work/events2.jsonl" "$work/track.txt" \
  "$work/picture.jpg" || fail "what the page was sent"
grep -q "^stillness = 3 " "$HOME/.config/hkf/hkf-filter.conf" || fail "the save did not write stillness 3"
# the whole text first, then grep: piped into grep -q under pipefail, the 7.8 kB (two writes) could meet a closed
# pipe once grep had its match, and hkf-filter's SIGPIPE failed the pipeline (a CI run did)
effective=$(HKF_SYSTEM_CONFIG_DIR="$work/none" "$build/tools/hkf-filter" --print-config) || fail "hkf-filter --print-config failed"
grep -q "^stillness *= 3 .*hkf-filter.conf:1" <<<"$effective" || fail "hkf-filter does not read the saved stillness back"
echo "view_live_test: ok"
