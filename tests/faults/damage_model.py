#!/usr/bin/env python3
"""Writes a damaged copy of an ONNX model for the hardening tests: the initializer NAME with its data cut
short by four elements, or with a huge declared shape. usage: damage_model.py IN.onnx OUT.onnx short|huge NAME"""
import sys

import onnx

model = onnx.load(sys.argv[1])
how, part = sys.argv[3], sys.argv[4]
tensor = next(t for t in model.graph.initializer if t.name == part)
if how == "short":
    tensor.raw_data = tensor.raw_data[:-16]  # four floats missing
else:
    del tensor.dims[:]
    tensor.dims.extend([1 << 30, 1 << 30, 3, 3])
onnx.save(model, sys.argv[2])
print(f"damage_model: {how} {tensor.name} ({onnx.TensorProto.DataType.Name(tensor.data_type)})")
