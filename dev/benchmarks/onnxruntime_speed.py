#!/usr/bin/env python3
"""Forward time of each converted network in onnxruntime (Python), 2 threads:
the reference beside OpenCV DNN's figures. usage: onnxruntime_speed.py MODELS_DIR"""
import os
import statistics
import sys
import time

import numpy as np
import onnxruntime

models = sys.argv[1]
options = onnxruntime.SessionOptions()
options.intra_op_num_threads = 2
print(f"onnxruntime {onnxruntime.__version__}, 2 threads, forward pass only:\n")
print("| network | p50 ms | frames/s at p50 |\n| --- | ---: | ---: |")
for name in ("face_detection_short_range", "face_landmark", "whenet"):
    session = onnxruntime.InferenceSession(os.path.join(models, name + ".onnx"), options, providers=["CPUExecutionProvider"])
    spec = session.get_inputs()[0]
    x = np.random.RandomState(0).rand(*spec.shape).astype(np.float32)
    for _ in range(5):
        session.run(None, {spec.name: x})
    times = []
    for _ in range(100):
        t0 = time.perf_counter()
        session.run(None, {spec.name: x})
        times.append(1000 * (time.perf_counter() - t0))
    p50 = statistics.median(times)
    print(f"| {name} | {p50:.1f} | {1000 / p50:.0f} |")
