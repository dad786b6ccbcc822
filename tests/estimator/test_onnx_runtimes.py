#!/usr/bin/env python3
"""Each converted network (BlazeFace short and full range, face mesh, WHENet)
gives the same outputs in OpenCV DNN (the estimator's runtime) as in
onnxruntime, on a real AFLW2000 face prepared as the estimator prepares it.
usage: test_onnx_runtimes.py BUILD_DIR DATA_DIR MODELS_DIR
"""
import os
import subprocess
import sys
import tempfile

import numpy as np
import onnxruntime
from PIL import Image

build, data, models = sys.argv[1:4]
image = Image.open(os.path.join(data, "images", "image00013.jpg")).convert("RGB")
face = image.crop((100, 140, 345, 400))

# (file, input size, preparation of an RGB uint8 array)
cases = [
    ("face_detection_short_range.onnx", 128, lambda a: a / 127.5 - 1.0),
    ("face_detection_full_range.onnx", 192, lambda a: a / 127.5 - 1.0),
    ("face_landmark.onnx", 192, lambda a: a / 255.0),
    ("whenet.onnx", 224, lambda a: (a / 255.0 - [0.485, 0.456, 0.406]) / [0.229, 0.224, 0.225]),
]
passed = failed = 0
for name, size, prepare in cases:
    path = os.path.join(models, name)
    session = onnxruntime.InferenceSession(path, providers=["CPUExecutionProvider"])
    rgb = np.asarray(face.resize((size, size), Image.BILINEAR), np.float32)
    x = np.ascontiguousarray(prepare(rgb).transpose(2, 0, 1)[None].astype(np.float32))
    names = [o.name for o in session.get_outputs()]
    outputs = session.run(names, {session.get_inputs()[0].name: x})
    with tempfile.NamedTemporaryFile(delete=False) as f:
        f.write(f"{path}\n{' '.join(map(str, x.shape))}\n{len(names)}\n".encode())
        for n, o in zip(names, outputs):
            f.write(f"{n} {o.size}\n".encode())
        f.write(x.astype("<f4").tobytes())
        for o in outputs:
            f.write(o.astype("<f4").tobytes())
        case = f.name
    run = subprocess.run([os.path.join(build, "tests", "test_onnx_runtimes"), case], capture_output=True, text=True)
    os.unlink(case)
    print(f"{name}:\n{run.stdout}{run.stderr}", end="")
    passed, failed = passed + (run.returncode == 0), failed + (run.returncode != 0)
print(f"{passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
