#!/usr/bin/env python3
"""Small ONNX graphs for fuzz_onnx_model's corpus, beside the shipped models: a convolution with a bias,
the estimator's own three layer types (hkf.DepthwiseConv, hkf.PointwiseConv, hkf.Swish) and a Constant
node, typed (not raw) data, an int64 shape and a graph inside an attribute (If).
usage: make_onnx_seeds.py OUT_DIR"""
import os
import sys

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper

out = sys.argv[1]
os.makedirs(out, exist_ok=True)
rng = np.random.RandomState(3)


def tensor(name, shape):
    return numpy_helper.from_array(rng.randn(*shape).astype(np.float32), name)


x = helper.make_tensor_value_info("x", TensorProto.FLOAT, [1, 4, 8, 8])
y = helper.make_tensor_value_info("y", TensorProto.FLOAT, None)
conv = helper.make_graph(
    [helper.make_node("Conv", ["x", "w", "b"], ["c"], kernel_shape=[3, 3], pads=[1, 1, 1, 1]),
     helper.make_node("Relu", ["c"], ["y"])],
    "conv", [x], [y], [tensor("w", (4, 4, 3, 3)), tensor("b", (4,))])
hkf = helper.make_graph(
    [helper.make_node("DepthwiseConv", ["x", "dw", "db"], ["d"], domain="hkf", kernel=3, stride=1, pad_top=1,
                      pad_left=1, pad_bottom=1, pad_right=1, swish=1),
     helper.make_node("PointwiseConv", ["d", "pw", "pb"], ["p"], domain="hkf", swish=0),
     helper.make_node("Swish", ["p"], ["s"], domain="hkf"),
     helper.make_node("Constant", [], ["k"], value=helper.make_tensor("kv", TensorProto.FLOAT, [1], [0.5])),
     helper.make_node("Mul", ["s", "k"], ["y"])],
    "hkf", [x], [y], [tensor("dw", (4, 1, 3, 3)), tensor("db", (4,)), tensor("pw", (8, 4, 1, 1)), tensor("pb", (8,))])
shape = helper.make_tensor("shape", TensorProto.INT64, [2], [1, 256])
typed = helper.make_graph(
    [helper.make_node("Reshape", ["x", "shape"], ["r"]),
     helper.make_node("MatMul", ["r", "m"], ["y"])],
    "typed", [x], [y], [shape, helper.make_tensor("m", TensorProto.FLOAT, [256, 2], list(rng.randn(512)))])
then = helper.make_graph([helper.make_node("Identity", ["x"], ["t"])], "then", [], [helper.make_tensor_value_info("t", TensorProto.FLOAT, None)])
other = helper.make_graph([helper.make_node("Neg", ["x"], ["e"])], "else", [], [helper.make_tensor_value_info("e", TensorProto.FLOAT, None)])
branch = helper.make_graph(
    [helper.make_node("Constant", [], ["c"], value=helper.make_tensor("cv", TensorProto.BOOL, [], [1])),
     helper.make_node("If", ["c"], ["y"], then_branch=then, else_branch=other)],
    "branch", [x], [y])
for graph in (conv, hkf, typed, branch):
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 11), helper.make_opsetid("hkf", 1)])
    onnx.save(model, os.path.join(out, graph.name + ".onnx"))
print(f"make_onnx_seeds: 4 graphs in {out}")
