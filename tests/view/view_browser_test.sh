#!/usr/bin/env bash
# The live view in a real browser (browser_test.py): hkf-track --view plays a real face video as the camera
# in a private network namespace; headless Chromium opens the page and is checked as a player would look.
# Needs root (unshare --net) and Chromium; exits 77 (skipped) otherwise.
# usage: view_browser_test.sh BUILD_DIR SOURCE_DIR PYTHON VIDEO_DIR [SCREENSHOT.png]
set -euo pipefail
trap 'echo "view_browser_test: line $LINENO failed" >&2' ERR
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd) python=$3 videos=$4 shot=${5:-}
chromium=$(command -v chromium || true)
[ -n "$chromium" ] || { echo "view_browser_test: no chromium (scripts/setup.sh installs it); skipped"; exit 77; }
if [ "${HKF_IN_NETNS:-}" != 1 ]; then
  HKF_IN_NETNS=1 exec "$source/tools/lcm-netns" "$0" "$@"
fi
work=$(mktemp -d)
track_pid=
cleanup() { [ -z "$track_pid" ] || kill "$track_pid" 2>/dev/null || true; rm -rf "$work"; }
trap cleanup EXIT
fail() { echo "FAIL: $*" >&2; tail -5 "$work/track.txt" >&2 2>/dev/null || true; exit 1; }
. "$source/tests/lib/wait_until.sh"
export HOME="$work/home" XDG_CONFIG_HOME=
mkdir -p "$HOME"
port=$((20000 + RANDOM % 20000))
"$build/tools/hkf-track" --source "$videos/d14.mp4" --realtime --view "$port" --logs "$work/logs" >"$work/track.txt" 2>&1 &
track_pid=$!
wait_until 60 "the view" curl -s -o /dev/null "http://127.0.0.1:$port/view.css" || fail "the view did not open"
"$python" "$source/tests/view/browser_test.py" "$chromium" "http://127.0.0.1:$port" "$work/track.txt" \
  "${shot:-$work/view.png}" || fail "the page in Chromium"
kill -INT "$track_pid"
wait "$track_pid" || fail "hkf-track did not stop cleanly"
track_pid=
echo "view_browser_test: ok"
