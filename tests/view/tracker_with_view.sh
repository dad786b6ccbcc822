# tracker_with_view.sh - sourced by the live view's tests (inside a private network namespace, after build,
# source and videos are set): a scratch folder, its cleanup and fail(); a home of the test's own (a save goes
# there, never to the user running the test); then start_tracker_with_view CLIP plays CLIP as a camera through
# hkf-track --view on a free port and waits for the page: $base is its address, $track_pid the tracker.
# stop_tracker stops it and checks it stopped cleanly.
work=$(mktemp -d)
track_pid=
cleanup() { [ -z "$track_pid" ] || kill "$track_pid" 2>/dev/null || true; rm -rf "$work"; }
trap cleanup EXIT
fail() { echo "FAIL: $*" >&2; tail -20 "$work/track.txt" >&2 2>/dev/null || true; exit 1; }
. "$source/tests/lib/wait_until.sh"
export HOME="$work/home" XDG_CONFIG_HOME=
mkdir -p "$HOME"
port=$((20000 + RANDOM % 20000))
base="http://127.0.0.1:$port"

start_tracker_with_view() { # start_tracker_with_view CLIP
  "$build/tools/hkf-track" --source "$1" --realtime --view "$port" --logs "$work/logs" >"$work/track.txt" 2>&1 &
  track_pid=$!
  wait_until 60 "the view" curl -s -o /dev/null "$base/view.css" || fail "the view did not open"
}

stop_tracker() {
  kill -INT "$track_pid"
  wait "$track_pid" || fail "hkf-track did not stop cleanly"
  track_pid=
}
