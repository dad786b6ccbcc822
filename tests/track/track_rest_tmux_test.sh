#!/usr/bin/env bash
# hkf-track asks for the player's rest, checked in a terminal (tmux) as a player sees it: a real video
# stands in for the camera (--realtime; d14, whose first seconds are moves, then a rest). The pane must
# show the request to keep still, a countdown that counts down, a rest spoiled by a move asked again,
# and the rest measured. Needs root (unshare --net) and tmux; exits 77 (skipped) otherwise.
# usage: track_rest_tmux_test.sh BUILD_DIR SOURCE_DIR VIDEO_DIR
set -euo pipefail
trap 'echo "track_rest_tmux_test: line $LINENO failed" >&2' ERR
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd) videos=$3

command -v tmux >/dev/null || { echo "track_rest_tmux_test: no tmux (apt-get install tmux)"; exit 77; }
if [ "${HKF_IN_NETNS:-}" != 1 ]; then
  HKF_IN_NETNS=1 exec "$source/tools/lcm-netns" "$0" "$@"
fi
work=$(mktemp -d)
session="hkf-rest-$$"
cleanup() { tmux kill-session -t "$session" 2>/dev/null || true; rm -rf "$work"; }
trap cleanup EXIT
fail() { echo "FAIL: $*" >&2; cat "$work/pane.txt" >&2 2>/dev/null || true; exit 1; }
. "$source/tests/lib/wait_until.sh"

# a terminal 240 columns wide, its whole history kept; the tracker stops by itself after 9 s
tmux -f /dev/null new-session -d -s "$session" -x 240 -y 60 \
  "'$build/tools/hkf-track' --source '$videos/d14.mp4' --realtime --seconds 9 --logs '$work/logs'; echo TRACK-EXIT \$?; sleep 60"
tmux set-option -t "$session" history-limit 5000 >/dev/null
pane() { tmux capture-pane -p -J -S - -t "$session" >"$work/pane.txt"; }
finished() { pane; grep -q "TRACK-EXIT" "$work/pane.txt"; }
wait_until 90 "hkf-track's end in the terminal" finished || fail "hkf-track did not end in the terminal"
pane
cat "$work/pane.txt"

grep -q "TRACK-EXIT 0" "$work/pane.txt" || fail "hkf-track did not exit 0"
grep -q "look at the screen's centre and keep still while the line counts down" "$work/pane.txt" ||
  fail "no request for the rest at the start"
# the countdown: the seconds left, line after line, count down within each rest asked for
sed -n "s/.*keep still: \([0-9.]*\) s.*/\1/p" "$work/pane.txt" >"$work/left.txt"
[ "$(wc -l <"$work/left.txt")" -ge 4 ] || fail "fewer than 4 countdown lines"
awk 'NR > 1 && $1 < prev { down++ } { prev = $1 } END { exit !(down >= 2) }' "$work/left.txt" ||
  fail "the countdown does not count down"
grep -q "keep still: [0-9.]* s (you moved: again)" "$work/pane.txt" || fail "a spoiled rest was not asked again"
grep -Eq "rest measured: the view holds still by [0-9.]+ deg\^2 \(--stillness 1\)" "$work/pane.txt" ||
  fail "the rest measured was not said"
# once measured, the request stops
awk '/rest measured: the view holds/ { seen = 1; next } seen && /keep still:/ { exit 1 }' "$work/pane.txt" ||
  fail "still asked to keep still after the rest was measured"
grep -q "hkf-filter: the player's rest: 1 measured, [1-9][0-9]* spoiled" "$work/pane.txt" ||
  fail "hkf-filter's summary does not count the rest"
echo "track_rest_tmux_test: the request, $(wc -l <"$work/left.txt") countdown lines, a spoiled rest asked again, the rest measured"
