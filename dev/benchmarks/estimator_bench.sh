#!/usr/bin/env bash
# The estimator's benchmarks: AFLW2000 MAE per model (the whole development
# split), per-stage cost on 640x480 video in OpenCV DNN beside onnxruntime,
# and the whole process fed a 640x480 video paced at 60 fps.
# usage: estimator_bench.sh BUILD_DIR [AFLW_DIR]
set -euo pipefail
build=$(cd "$1" && pwd)
root=$(cd "$(dirname "$0")/../.." && pwd)
aflw=${2:-$root/../shared/data/aflw2000}
models=$root/.models
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

echo "## AFLW2000 (development split of $(($(wc -l <"$aflw/labels.csv") - 1)) images): the live path, then the labels' face boxes"
for crop in live labels; do
  for model in whenet mesh_pnp; do
    "$build/estimator/hkf-estimator" --dataset "$aflw" --crop "$crop" --model "$model" --second-model none --predictions "$work/$model.csv" 2>/dev/null
  done
done
echo
echo "## Per-stage cost"
"$build/dev/benchmarks/hkf-bench-estimator" "$root/../shared/data/videos/d3.mp4" "$models" "$root/estimator/models" "$work/640x480_60fps.mp4"
echo
"$root/.venv/bin/python" "$root/dev/benchmarks/onnxruntime_speed.py" "$models"
echo
echo "## The whole process on 640x480 video paced at 60 fps (--realtime)"
for model in whenet mesh_pnp; do
  printf '%s alone: ' "$model"
  "$build/estimator/hkf-estimator" --source "$work/640x480_60fps.mp4" --realtime --model "$model" --second-model none \
    --lcm-url memq:// 2>/dev/null
done
# mesh_pnp with WHENet on the second thread: asked for every frame (the worst
# case: a driver turned beyond the threshold the whole time), and as by default
# (the default pipeline: |yaw| >= 10 deg or no mesh pose; this clip stays within about 15 deg)
for from_yaw in 0 10; do
  echo "mesh_pnp + --second-model whenet --second-from-yaw $from_yaw:"
  "$build/estimator/hkf-estimator" --source "$work/640x480_60fps.mp4" --realtime --model mesh_pnp --second-model whenet \
    --second-from-yaw "$from_yaw" --lcm-url memq:// 2>/dev/null
done
echo
echo "## Re-acquire: the face leaves and comes back (dev/benchmarks/reacquire.py)"
"$root/.venv/bin/python" "$root/dev/benchmarks/reacquire.py" "$build" "$root/../shared/data/videos/d3.mp4" \
  "$models/testdata/no_face.mp4" 3
