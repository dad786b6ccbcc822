#!/usr/bin/env python3
"""Rewrites a converted ONNX graph (WHENet's EfficientNet-B0) onto the two layers the estimator
gives OpenCV's DNN module (estimator/src/models/fast_layers.hpp), with onnx alone:
- every swish, Mul(x, Sigmoid(x)), becomes one node hkf.Swish(x);
- every depthwise Conv (group = channels, one input channel per group) becomes hkf.DepthwiseConv,
  its padding as four attributes, and a swish right after it taken in (attribute swish = 1).
The weights and every other node stay as they are, so the network computes the same function
(up to float rounding: the swish's exp is a polynomial, the sums' order differs).
Usage: fast_layers.py IN.onnx OUT.onnx
"""
import argparse
import sys

import onnx
from onnx import helper, numpy_helper

DOMAIN = "hkf"


def attribute(node, name, default=None):
    for a in node.attribute:
        if a.name == name:
            return helper.get_attribute_value(a)
    return default


def consumers_of(nodes):
    table = {}
    for node in nodes:
        for name in node.input:
            table.setdefault(name, []).append(node)
    return table


def fuse_swish(nodes):
    """Mul(x, Sigmoid(x)) -> hkf.Swish(x); returns the new node list and how many were fused."""
    producers = {out: node for node in nodes for out in node.output}
    drop, replaced, count = set(), {}, 0
    for node in nodes:
        if node.op_type != "Mul" or len(node.input) != 2:
            continue
        for x, s in (node.input, reversed(node.input)):
            sigmoid = producers.get(s)
            if sigmoid is not None and sigmoid.op_type == "Sigmoid" and sigmoid.input[0] == x:
                if len(consumers_of(nodes).get(s, [])) != 1:
                    continue  # the sigmoid is read elsewhere too: leave it
                drop.add(id(sigmoid))
                replaced[id(node)] = helper.make_node("Swish", [x], list(node.output), name=node.name, domain=DOMAIN)
                count += 1
                break
    return [replaced.get(id(n), n) for n in nodes if id(n) not in drop], count


def depthwise(node, weights):
    """The hkf.DepthwiseConv for a Conv node, or None when it is not depthwise."""
    if node.op_type != "Conv" or len(node.input) != 3 or node.input[1] not in weights:
        return None
    w = weights[node.input[1]]
    group = attribute(node, "group", 1)
    kernel = attribute(node, "kernel_shape", list(w.shape[2:]))
    strides = attribute(node, "strides", [1, 1])
    pads = attribute(node, "pads", [0, 0, 0, 0])
    dilations = attribute(node, "dilations", [1, 1])
    if (w.ndim != 4 or w.shape[1] != 1 or group != w.shape[0] or group < 2 or kernel[0] != kernel[1] or
            strides[0] != strides[1] or list(dilations) != [1, 1] or attribute(node, "auto_pad") not in (None, b"NOTSET")):
        return None
    return helper.make_node("DepthwiseConv", list(node.input), list(node.output), name=node.name, domain=DOMAIN,
                            kernel=int(kernel[0]), stride=int(strides[0]), pad_top=int(pads[0]),
                            pad_left=int(pads[1]), pad_bottom=int(pads[2]), pad_right=int(pads[3]), swish=0)


def fuse_depthwise(nodes, weights):
    """Depthwise Conv -> hkf.DepthwiseConv, taking in an hkf.Swish that alone reads it."""
    out, drop, count = [], set(), 0
    consumers = consumers_of(nodes)
    for node in nodes:
        if id(node) in drop:
            continue
        new = depthwise(node, weights)
        if new is None:
            out.append(node)
            continue
        readers = consumers.get(node.output[0], [])
        if len(readers) == 1 and readers[0].op_type == "Swish" and readers[0].domain == DOMAIN:
            drop.add(id(readers[0]))
            new.output[0] = readers[0].output[0]
            for a in new.attribute:
                if a.name == "swish":
                    a.i = 1
        out.append(new)
        count += 1
    return out, count


def rewrite(model):
    weights = {t.name: numpy_helper.to_array(t) for t in model.graph.initializer}
    nodes = list(model.graph.node)
    nodes, swishes = fuse_swish(nodes)
    nodes, convolutions = fuse_depthwise(nodes, weights)
    del model.graph.node[:]
    model.graph.node.extend(nodes)
    model.opset_import.append(helper.make_opsetid(DOMAIN, 1))
    return swishes, convolutions


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("source", help="the converted ONNX graph (not changed)")
    parser.add_argument("target", help="the rewritten graph to write")
    args = parser.parse_args()
    try:
        model = onnx.load(args.source)
        swishes, convolutions = rewrite(model)
        onnx.checker.check_model(model)
        onnx.save(model, args.target)
    except (OSError, ValueError, onnx.checker.ValidationError) as e:
        print(f"fast_layers: {e}", file=sys.stderr)
        return 1
    print(f"fast_layers: wrote {args.target}: {swishes} swishes, {convolutions} depthwise convolutions "
          f"({len(model.graph.node)} nodes)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
