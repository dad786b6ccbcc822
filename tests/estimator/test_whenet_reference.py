#!/usr/bin/env python3
"""WHENet on real AFLW2000 faces, three ways, must agree to 0.01 deg:
1. the original Keras weights run with NumPy in Keras's terms (whenet_reference.py);
2. our converted ONNX model run by onnxruntime;
3. the same ONNX model run by the estimator's C++ code on OpenCV DNN
   (test_pose_model_reference, fed the exact input tensors), once per instruction-set level of the
   estimator's own layers (HKF_SIMD: avx512, avx2, avx, sse2; a level this CPU lacks is skipped, said).
usage: test_whenet_reference.py BUILD_DIR SOURCE_DIR DATA_DIR MODELS_DIR
"""
import csv
import os
import struct
import subprocess
import sys
import tempfile

import numpy as np
import onnxruntime
from PIL import Image

build, source, data, models = sys.argv[1:5]
sys.path.insert(0, os.path.join(source, "dev", "models"))
import whenet_reference as ref  # noqa: E402

MEAN = np.array([0.485, 0.456, 0.406], np.float32)
STD = np.array([0.229, 0.224, 0.225], np.float32)
BINS = {"yaw": (3.0, -180.0), "pitch": (3.0, -99.0), "roll": (3.0, -99.0)}
SIGNS = (1.0, 1.0, -1.0)  # estimator/models/whenet.model: model -> hkf convention (pitch yaw roll)
TOLERANCE = 0.01

rows = list(csv.DictReader(open(os.path.join(data, "labels.csv"))))
# a spread of poses: the first faces turned left, right, up, down, and frontal
picks = []
for test in (lambda y, p: y > 40, lambda y, p: y < -40, lambda y, p: p > 20, lambda y, p: p < -20,
             lambda y, p: abs(y) < 10 and abs(p) < 10):
    for r in rows:
        if test(float(r["yaw_deg"]), float(r["pitch_deg"])) and r not in picks:
            picks.append(r)
            break

session = onnxruntime.InferenceSession(os.path.join(models, "whenet.onnx"), providers=["CPUExecutionProvider"])
inputs, expected, failures = [], [], 0
print(f"{'image':16} {'numpy yaw/pitch/roll':>26} {'onnxruntime':>26}  max diff")
for r in picks:
    image = Image.open(os.path.join(data, "images", r["image"])).convert("RGB")
    x0, y0, x1, y1 = (float(r[k]) for k in ("x_min", "y_min", "x_max", "y_max"))
    w, h = x1 - x0, y1 - y0
    box = (int(max(0, x0 - 0.2 * w)), int(max(0, y0 - 0.2 * h)), int(min(image.width, x1 + 0.2 * w)),
           int(min(image.height, y1 + 0.2 * h)))
    rgb = np.asarray(image.crop(box).resize((224, 224), Image.BILINEAR), np.float32) / 255.0
    nhwc = ((rgb - MEAN) / STD)[None].astype(np.float32)
    keras = [ref.decode(l[0], *BINS[n]) for l, n in zip(ref.whenet_logits(os.path.join(models, "WHENet.h5"),
                                                                           nhwc.astype(np.float64)), ("yaw", "pitch", "roll"))]
    nchw = np.ascontiguousarray(nhwc.transpose(0, 3, 1, 2))
    yaw, pitch, roll = session.run(["yaw", "pitch", "roll"], {"input": nchw})
    ort = [ref.decode(yaw[0].astype(np.float64), *BINS["yaw"]), ref.decode(pitch[0].astype(np.float64), *BINS["pitch"]),
           ref.decode(roll[0].astype(np.float64), *BINS["roll"])]
    diff = max(abs(a - b) for a, b in zip(keras, ort))
    failures += diff > TOLERANCE
    print(f"{r['image']:16} {keras[0]:8.3f} {keras[1]:8.3f} {keras[2]:8.3f} {ort[0]:8.3f} {ort[1]:8.3f} {ort[2]:8.3f}  {diff:.5f}")
    inputs.append(nchw)
    expected.append([SIGNS[0] * ort[1], SIGNS[1] * ort[0], SIGNS[2] * ort[2]])  # hkf order: pitch yaw roll

# the same tensors through the estimator's OpenCV code
with tempfile.NamedTemporaryFile(suffix=".bin", delete=False) as f:
    f.write(struct.pack("<iiii", len(inputs), 3, 224, 224))
    for x, e in zip(inputs, expected):
        f.write(x.astype("<f4").tobytes())
        f.write(np.array(e, "<f4").tobytes())
    path = f.name
levels_run, levels_failed = [], 0
for level in ("avx512", "avx2", "avx", "sse2"):
    run = subprocess.run([os.path.join(build, "tests", "test_pose_model_reference"), path, models,
                          os.path.join(source, "estimator", "models")], capture_output=True, text=True,
                         env=dict(os.environ, HKF_SIMD=level))
    if "this CPU cannot run it" in run.stderr:
        print(f"the estimator's layers at {level}: skipped (this CPU cannot run it)")
        continue
    print(f"the estimator's layers at {level}:")
    print(run.stdout, end="")
    print(run.stderr, end="", file=sys.stderr)
    levels_run.append(level)
    levels_failed += run.returncode != 0
os.unlink(path)
checks = len(picks) + len(levels_run)
failed = failures + levels_failed + (not levels_run)
print(f"{checks - failed} passed, {failed} failed")
sys.exit(1 if failed or len(picks) < 5 else 0)
