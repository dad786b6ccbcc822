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
. "$source/tests/view/tracker_with_view.sh"
start_tracker_with_view "$videos/d14.mp4"
"$python" "$source/tests/view/browser_test.py" "$chromium" "$base" "$work/track.txt" "${shot:-$work/view.png}" ||
  fail "the page in Chromium"
stop_tracker
echo "view_browser_test: ok"
