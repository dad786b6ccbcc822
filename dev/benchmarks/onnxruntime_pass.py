#!/usr/bin/env python3
"""One network's forward pass in onnxruntime (Python, CPU): the median of RUNS passes on THREADS threads, and the
vector features this process's CPU reports (what onnxruntime's kernels choose by), so that a figure said to be at a
level can be checked to be at it (layer_levels.sh plays lower levels with cpu_level_mask.c).
Prints one line: MS AVX AVX2 AVX512F, the last three 0 or 1.
usage: onnxruntime_pass.py MODEL.onnx THREADS RUNS"""
import statistics
import sys
import time

import numpy as np
import onnxruntime
from numpy._core._multiarray_umath import __cpu_features__ as cpu_features

if len(sys.argv) != 4 or sys.argv[1] in ("--help", "-h"):
    print(__doc__.strip())
    sys.exit(0 if len(sys.argv) == 2 else 2)
model, threads, runs = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
options = onnxruntime.SessionOptions()
options.intra_op_num_threads = threads
session = onnxruntime.InferenceSession(model, options, providers=["CPUExecutionProvider"])
spec = session.get_inputs()[0]
x = np.random.RandomState(0).rand(*spec.shape).astype(np.float32)
for _ in range(5):
    session.run(None, {spec.name: x})
times = []
for _ in range(runs):
    start = time.perf_counter()
    session.run(None, {spec.name: x})
    times.append(1000 * (time.perf_counter() - start))
flags = " ".join(str(int(bool(cpu_features.get(name)))) for name in ("AVX", "AVX2", "AVX512F"))
print(f"{statistics.median(times):.2f} {flags}")
