#!/usr/bin/env bash
# hkf-view's door over real HTTP (memq://: no tracker needed): the page and its assets are served with the
# run's token in the page; a foreign Host, a foreign Origin, a command without the token or with a wrong
# one, a path outside the assets and another method are refused; viewers beyond --max-viewers are refused;
# 100 viewers that connect and drop leave it answering; its command line is checked.
# usage: view_server_test.sh BUILD_DIR
set -euo pipefail
trap 'echo "view_server_test: line $LINENO failed" >&2' ERR
build=$(cd "$1" && pwd)
view="$build/tools/hkf-view"
work=$(mktemp -d)
pid=
cleanup() { [ -z "$pid" ] || kill "$pid" 2>/dev/null || true; rm -rf "$work"; }
trap cleanup EXIT
fail() { echo "FAIL: $*" >&2; cat "$work/view.txt" >&2 2>/dev/null || true; exit 1; }
code() { curl -s -o /dev/null -w '%{http_code}' --max-time 5 "$@"; }

"$view" --help | grep -q -- "--listen" || fail "--help"
"$view" --version | grep -q "^hkf-view " || fail "--version"
exit_of() { local status=0; "$@" 2>>"$work/err.txt" || status=$?; echo "$status"; }
[ "$(exit_of "$view" --listen example.org:80)" = 2 ] || fail "a host name to listen on is not exit 2"
grep -q "not an IPv4 address" "$work/err.txt" || fail "no reason for a host name"
[ "$(exit_of "$view" --listen 70000)" = 2 ] || fail "port 70000 is not exit 2"
[ "$(exit_of "$view" --max-viewers 0)" = 2 ] || fail "--max-viewers 0 is not exit 2"

port=$((20000 + RANDOM % 20000))
base="http://127.0.0.1:$port"
"$view" --lcm-url memq:// --listen "127.0.0.1:$port" --max-viewers 3 --seconds 60 >"$work/view.txt" 2>&1 &
pid=$!
for _ in $(seq 50); do [ "$(code "$base/view.css")" = 200 ] && break; sleep 0.1; done
grep -q "http://127.0.0.1:$port/ (this computer only)" "$work/view.txt" || fail "the start does not say where"

# the page, its assets, the token
curl -s "$base/" >"$work/page.html"
token=$(sed -n 's/.*name="hkf-token" content="\([0-9a-f]\{32\}\)".*/\1/p' "$work/page.html")
[ -n "$token" ] || fail "the page carries no token"
[ "$(code "$base/view.js")" = 200 ] || fail "view.js"
curl -s -D - -o /dev/null "$base/" | grep -qi "^content-security-policy: default-src 'self'" || fail "no CSP"

# refused, each one
[ "$(code -H "Host: evil.example:$port" "$base/")" = 421 ] || fail "a foreign Host (DNS rebinding) was served"
[ "$(code -H "Host: 127.0.0.1" "$base/")" = 421 ] || fail "a Host without the view's port was served"
[ "$(code -H "Origin: http://evil.example" "$base/")" = 403 ] || fail "a foreign Origin was served"
[ "$(code -H "Sec-Fetch-Site: cross-site" "$base/view.css")" = 403 ] || fail "another site's <img> or <script> was served"
[ "$(code -X POST -H "Origin: http://evil.example" -H "X-HKF-Token: $token" "$base/command/recenter")" = 403 ] ||
  fail "a command from a foreign page was taken, token or not"
[ "$(code -X POST "$base/command/recenter")" = 403 ] || fail "a command without the token was taken"
# a wrong token: the right one with its last digit changed (to 1 if it was 0, else to 0)
wrong="${token%?}0"; [ "$wrong" != "$token" ] || wrong="${token%?}1"
[ "$(code -X POST -H "X-HKF-Token: $wrong" "$base/command/recenter")" = 403 ] || fail "a wrong token was taken"
[ "$(code -X POST -H "X-HKF-Token: $token" "$base/command/format")" = 400 ] || fail "an unknown command was taken"
for path in /../../etc/passwd /index.html /view.js/ /etc/passwd /%2e%2e/%2e%2e/etc/passwd /.git/config; do
  [ "$(code --path-as-is "$base$path")" = 404 ] || fail "$path is served (only the page's assets may be)"
done
[ "$(code -X PUT "$base/")" = 405 ] || fail "PUT was taken"
[ "$(code "$base/picture.jpg")" = 404 ] || fail "a picture before any came"
# the token taken: the command is sent
[ "$(code -X POST -H "X-HKF-Token: $token" -H "Origin: http://127.0.0.1:$port" "$base/command/recenter")" = 200 ] ||
  fail "the page's own command was refused"

# viewers: three streams open, a fourth refused; then 100 that connect and drop
streams=()
for i in 1 2 3; do curl -s -N --max-time 8 "$base/events" >"$work/stream$i.txt" & streams+=($!); done
# each of the three in first (a stream's first bytes, an event or a keep-alive, come within 250 ms): a probe
# that came before one of them would take its place (on a loaded machine curl starts late)
for _ in $(seq 50); do [ -s "$work/stream1.txt" ] && [ -s "$work/stream2.txt" ] && [ -s "$work/stream3.txt" ] && break
  sleep 0.1; done
refused=0  # once the three are in, a fourth is refused (probed until then: a slow machine takes a while)
for _ in $(seq 20); do [ "$(code --max-time 0.5 "$base/events")" = 503 ] && { refused=1; break; }; sleep 0.1; done
[ "$refused" = 1 ] || fail "a fourth viewer beyond --max-viewers 3 was taken"
wait "${streams[@]}" || true  # curl ends them at --max-time
grep -q '^data: {"t":"line"' "$work/stream1.txt" || fail "a viewer got no status line in 8 s"
for _ in $(seq 100); do curl -s -N --max-time 0.05 "$base/events" >/dev/null || true; done
[ "$(code "$base/view.css")" = 200 ] || fail "100 viewers that dropped left it unanswering"
# their streams end once a keep-alive finds each one gone (within a second); a new viewer is then taken
for _ in $(seq 20); do [ "$(code --max-time 1 "$base/events")" = 503 ] || break; sleep 0.5; done
curl -s -N --max-time 2 "$base/events" >"$work/after.txt" || true  # curl ends the stream at --max-time
grep -q '"t":"line"' "$work/after.txt" || fail "a viewer after the 100 got nothing"

kill -INT "$pid"
wait "$pid" || fail "hkf-view did not stop cleanly on SIGINT"
pid=
grep -q "hkf-view: 1 commands, 7 requests refused" "$work/view.txt" || fail "the summary's counts"
echo "view_server_test: ok"
