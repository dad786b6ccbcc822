#!/usr/bin/env python3
"""Small ONNX graphs for fuzz_onnx_model's corpus, beside the shipped models: a convolution with a bias,
the estimator's own layer types (hkf.DepthwiseConv, hkf.PointwiseConv, hkf.UnfoldedConv, hkf.SqueezeExcite,
hkf.Swish) and a Constant
node, typed (not raw) data, an int64 shape and a graph inside an attribute (If); and three whose singular
messages are given more than once, which protobuf merges (hardening round 6): the model's graph in two
occurrences, a Constant's tensor whose dims and data come in two, an If's branch graph in two.
usage: make_onnx_seeds.py OUT_DIR"""
import os
import sys

import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from protobuf_bytes import field  # noqa: E402

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
     helper.make_node("UnfoldedConv", ["p", "uw", "ub"], ["u"], domain="hkf", kernel=3, stride=2, pad_top=0,
                      pad_left=0, pad_bottom=1, pad_right=1, swish=0),
     helper.make_node("Swish", ["u"], ["s"], domain="hkf"),
     helper.make_node("GlobalAveragePool", ["s"], ["m"]),
     helper.make_node("SqueezeExcite", ["m", "sw1", "sb1", "sw2", "sb2"], ["g"], domain="hkf"),
     helper.make_node("Mul", ["s", "g"], ["sg"]),
     helper.make_node("Constant", [], ["k"], value=helper.make_tensor("kv", TensorProto.FLOAT, [1], [0.5])),
     helper.make_node("Mul", ["sg", "k"], ["y"])],
    "hkf", [x], [y], [tensor("dw", (4, 1, 3, 3)), tensor("db", (4,)), tensor("pw", (8, 4, 1, 1)), tensor("pb", (8,)),
                tensor("uw", (6, 8, 3, 3)), tensor("ub", (6,)), tensor("sw1", (2, 6, 1, 1)), tensor("sb1", (2,)),
                tensor("sw2", (6, 2, 1, 1)), tensor("sb2", (6,))])
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


def model_bytes(graph):
    return helper.make_model(graph, opset_imports=[helper.make_opsetid("", 11)]).SerializeToString()


# the model's graph (ModelProto field 7) in two occurrences: the first's nodes, then the rest
head = helper.make_graph([conv.node[0]], "conv", [x], [y], list(conv.initializer))
tail = onnx.GraphProto()
tail.node.extend([conv.node[1]])
with open(os.path.join(out, "graph_twice.onnx"), "wb") as f:
    f.write(model_bytes(head) + field(7, tail.SerializeToString()))
# a Constant's tensor (AttributeProto field 5) in two occurrences: dims [2] then dims [3], data_type and 24 bytes
first_part, second_part = onnx.TensorProto(), onnx.TensorProto()
first_part.dims.extend([2])
second_part.dims.extend([3])
second_part.data_type = TensorProto.FLOAT
second_part.raw_data = np.zeros(6, np.float32).tobytes()
attribute = onnx.AttributeProto()
attribute.name, attribute.type = "value", onnx.AttributeProto.TENSOR
attribute_bytes = attribute.SerializeToString() + field(5, first_part.SerializeToString()) + \
    field(5, second_part.SerializeToString())
node = helper.make_node("Constant", [], ["k"])
node_bytes = node.SerializeToString() + field(5, attribute_bytes)
graph = helper.make_graph([helper.make_node("Identity", ["x"], ["y"])], "tensor_twice", [x], [y])
with open(os.path.join(out, "tensor_twice.onnx"), "wb") as f:
    f.write(model_bytes(graph) + field(7, field(1, node_bytes)))
# an If's then-branch (AttributeProto field 6) in two occurrences: its name and output, then its node
then_head = helper.make_graph([], "then", [], [helper.make_tensor_value_info("t", TensorProto.FLOAT, None)])
then_tail = onnx.GraphProto()
then_tail.node.extend([helper.make_node("Identity", ["x"], ["t"])])
branch_attribute = onnx.AttributeProto()
branch_attribute.name, branch_attribute.type = "then_branch", onnx.AttributeProto.GRAPH
branch_attribute_bytes = branch_attribute.SerializeToString() + field(6, then_head.SerializeToString()) + \
    field(6, then_tail.SerializeToString())
if_node = helper.make_node("If", ["c"], ["y"], else_branch=other)
if_bytes = if_node.SerializeToString() + field(5, branch_attribute_bytes)
branch_head = helper.make_graph([branch.node[0]], "branch_twice", [x], [y])
with open(os.path.join(out, "branch_twice.onnx"), "wb") as f:
    f.write(model_bytes(branch_head) + field(7, field(1, if_bytes)))
print(f"make_onnx_seeds: 7 graphs in {out} (3 with singular messages given twice)")
