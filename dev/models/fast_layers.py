#!/usr/bin/env python3
"""Rewrites a converted ONNX graph (WHENet's EfficientNet-B0) onto the layers the estimator
gives OpenCV's DNN module (estimator/src/models/fast_layers.hpp), with onnx alone:
- every swish, Mul(x, Sigmoid(x)), becomes one node hkf.Swish(x);
- every depthwise Conv (group = channels, one input channel per group) becomes hkf.DepthwiseConv,
  its padding as four attributes, and a swish right after it taken in (attribute swish = 1);
- every 1x1 Conv (stride 1, no padding) on planes of at least MIN_PIXELS pixels becomes
  hkf.PointwiseConv, a swish after it taken in likewise (the squeeze-and-excitation's 1x1 convolutions,
  on one pixel, stay OpenCV's);
- every other dense Conv (one group, a square kernel, one stride; WHENet's first, 3x3 at stride 2) on
  such planes becomes hkf.UnfoldedConv, the same product over its unfolded input, its padding and a
  swish after it taken in likewise;
- a squeeze-and-excitation's two 1x1 convolutions on its means (Conv, swish, Conv, Sigmoid) become one
  hkf.SqueezeExcite (sixty tiny OpenCV layers fewer, each a parallel region of its own);
- a squeeze-and-excitation's gate, Mul(x, Sigmoid(s)) read only by such a pointwise convolution, becomes
  that convolution's second input (it scales the weights); its global average pooling of a depthwise
  convolution's output becomes that convolution's second output;
- a residual Add(y, skip) of a pointwise convolution's output y that only it reads becomes that
  convolution's last input (attribute residual = 1): the sum is taken as each output tile is written.
The weights and every other node stay as they are, so the network computes the same function
(up to float rounding: the swish's exp is a polynomial, the sums' order differs).
Usage: fast_layers.py IN.onnx OUT.onnx
"""
import argparse
import sys

import onnx
from onnx import helper, numpy_helper

DOMAIN = "hkf"
MIN_PIXELS = 16  # below, a pointwise tile (16-48 pixels) would be mostly padding


def attribute(node, name, default=None):
    for a in node.attribute:
        if a.name == name:
            return helper.get_attribute_value(a)
    return default


def set_attribute(node, name, value):
    for a in node.attribute:
        if a.name == name:
            a.i = value


def consumers_of(nodes):
    table = {}
    for node in nodes:
        for name in node.input:
            table.setdefault(name, []).append(node)
    return table


def producers_of(nodes):
    return {out: node for node in nodes for out in node.output}


def fuse_swish(nodes):
    """Mul(x, Sigmoid(x)) -> hkf.Swish(x); returns the new node list and how many were fused."""
    producers, consumers = producers_of(nodes), consumers_of(nodes)
    drop, replaced, count = set(), {}, 0
    for node in nodes:
        if node.op_type != "Mul" or len(node.input) != 2:
            continue
        for x, s in (node.input, reversed(node.input)):
            sigmoid = producers.get(s)
            if sigmoid is not None and sigmoid.op_type == "Sigmoid" and sigmoid.input[0] == x:
                if len(consumers.get(s, [])) != 1:
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
                            pad_left=int(pads[1]), pad_bottom=int(pads[2]), pad_right=int(pads[3]), swish=0, means=0)


def pointwise(node, weights, pixels):
    """The hkf.PointwiseConv for a Conv node, or None when it is not a 1x1 convolution on a plane
    of MIN_PIXELS or more (pixels: input name -> H * W, from ONNX's shape inference)."""
    if node.op_type != "Conv" or len(node.input) not in (2, 3) or node.input[1] not in weights:
        return None
    w = weights[node.input[1]]
    if (w.ndim != 4 or w.shape[2:] != (1, 1) or attribute(node, "group", 1) != 1 or
            list(attribute(node, "strides", [1, 1])) != [1, 1] or list(attribute(node, "pads", [0, 0, 0, 0])) != [0] * 4 or
            list(attribute(node, "dilations", [1, 1])) != [1, 1] or attribute(node, "auto_pad") not in (None, b"NOTSET") or
            pixels.get(node.input[0], 0) < MIN_PIXELS):
        return None
    return helper.make_node("PointwiseConv", list(node.input), list(node.output), name=node.name, domain=DOMAIN, swish=0)


def unfolded(node, weights, pixels):
    """The hkf.UnfoldedConv for a Conv node, or None when it is not a dense (one group) convolution of a
    square kernel larger than 1, one stride and explicit padding, on a plane of MIN_PIXELS or more."""
    if node.op_type != "Conv" or len(node.input) not in (2, 3) or node.input[1] not in weights:
        return None
    w = weights[node.input[1]]
    kernel = list(attribute(node, "kernel_shape", list(w.shape[2:])))
    strides = list(attribute(node, "strides", [1, 1]))
    pads = list(attribute(node, "pads", [0, 0, 0, 0]))
    if (w.ndim != 4 or attribute(node, "group", 1) != 1 or kernel[0] != kernel[1] or kernel[0] < 2 or
            list(w.shape[2:]) != kernel or strides[0] != strides[1] or max(pads) >= kernel[0] or
            list(attribute(node, "dilations", [1, 1])) != [1, 1] or attribute(node, "auto_pad") not in (None, b"NOTSET") or
            pixels.get(node.input[0], 0) < MIN_PIXELS):
        return None
    return helper.make_node("UnfoldedConv", list(node.input), list(node.output), name=node.name, domain=DOMAIN,
                            kernel=int(kernel[0]), stride=int(strides[0]), pad_top=int(pads[0]), pad_left=int(pads[1]),
                            pad_bottom=int(pads[2]), pad_right=int(pads[3]), swish=0)


def plane_pixels(model):
    """Each tensor's H * W where shape inference knows it (4-d tensors)."""
    inferred = onnx.shape_inference.infer_shapes(model)
    pixels = {}
    for info in list(inferred.graph.value_info) + list(inferred.graph.input):
        dims = [d.dim_value for d in info.type.tensor_type.shape.dim]
        if len(dims) == 4 and dims[2] > 0 and dims[3] > 0:
            pixels[info.name] = dims[2] * dims[3]
    return pixels


def fuse_convolutions(nodes, weights, pixels):
    """Depthwise Conv -> hkf.DepthwiseConv, 1x1 Conv -> hkf.PointwiseConv, another dense Conv ->
    hkf.UnfoldedConv, each taking in an
    hkf.Swish that alone reads it. Returns the nodes and how many of each."""
    out, drop, counts = [], set(), {"DepthwiseConv": 0, "PointwiseConv": 0, "UnfoldedConv": 0}
    consumers = consumers_of(nodes)
    for node in nodes:
        if id(node) in drop:
            continue
        new = depthwise(node, weights) or pointwise(node, weights, pixels) or unfolded(node, weights, pixels)
        if new is None:
            out.append(node)
            continue
        readers = consumers.get(node.output[0], [])
        if len(readers) == 1 and readers[0].op_type == "Swish" and readers[0].domain == DOMAIN:
            drop.add(id(readers[0]))
            new.output[0] = readers[0].output[0]
            set_attribute(new, "swish", 1)
        out.append(new)
        counts[new.op_type] += 1
    return out, counts


def fuse_gates(nodes):
    """Mul(x, Sigmoid(s)) read only by an hkf.PointwiseConv -> the gate as its last input."""
    producers, consumers = producers_of(nodes), consumers_of(nodes)
    drop, count = set(), 0
    for node in nodes:
        if node.op_type != "Mul" or len(node.input) != 2:
            continue
        readers = consumers.get(node.output[0], [])
        if len(readers) != 1 or readers[0].op_type != "PointwiseConv" or readers[0].input[0] != node.output[0]:
            continue
        for x, g in (node.input, list(reversed(node.input))):
            gate = producers.get(g)
            if gate is not None and gate.op_type == "Sigmoid" and gate.input[0] != x:
                readers[0].input[0] = x
                readers[0].input.append(g)
                drop.add(id(node))
                count += 1
                break
    return [n for n in nodes if id(n) not in drop], count


def fuse_residuals(nodes):
    """Add(y, skip), y an hkf.PointwiseConv's output that only the Add reads -> skip as that convolution's
    last input (attribute residual = 1), its output the Add's; returns the nodes and how many."""
    producers, consumers = producers_of(nodes), consumers_of(nodes)
    drop, count = set(), 0
    for node in nodes:
        if node.op_type != "Add" or len(node.input) != 2 or node.input[0] == node.input[1]:
            continue
        for y, skip in (node.input, list(reversed(node.input))):
            conv = producers.get(y)
            if (conv is not None and conv.op_type == "PointwiseConv" and conv.domain == DOMAIN and
                    len(consumers.get(y, [])) == 1 and attribute(conv, "residual", 0) == 0):
                conv.input.append(skip)
                conv.output[0] = node.output[0]
                conv.attribute.append(helper.make_attribute("residual", 1))
                drop.add(id(node))
                count += 1
                break
    return [n for n in nodes if id(n) not in drop], count


def fuse_excitations(nodes, weights):
    """A squeeze-and-excitation's two 1x1 convolutions on its means, Conv -> hkf.Swish -> Conv -> Sigmoid,
    each read only by the next -> one hkf.SqueezeExcite (its four weights as inputs); returns the nodes
    and how many."""
    producers, consumers = producers_of(nodes), consumers_of(nodes)

    def only_reader(node, op_type):
        readers = consumers.get(node.output[0], [])
        return readers[0] if len(readers) == 1 and readers[0].op_type == op_type else None

    def on_one_pixel(conv):  # a 1x1 convolution with weights and a bias, one group
        return (conv is not None and conv.op_type == "Conv" and len(conv.input) == 3 and conv.input[1] in weights and
                conv.input[2] in weights and weights[conv.input[1]].ndim == 4 and
                weights[conv.input[1]].shape[2:] == (1, 1) and attribute(conv, "group", 1) == 1)

    drop, replaced, count = set(), {}, 0
    for reduce in nodes:
        swish = only_reader(reduce, "Swish") if on_one_pixel(reduce) else None
        expand = only_reader(swish, "Conv") if swish is not None else None
        sigmoid = only_reader(expand, "Sigmoid") if on_one_pixel(expand) else None
        if sigmoid is None or producers.get(reduce.input[0]) is None:
            continue
        replaced[id(reduce)] = helper.make_node(
            "SqueezeExcite", [reduce.input[0], reduce.input[1], reduce.input[2], expand.input[1], expand.input[2]],
            list(sigmoid.output), name=reduce.name, domain=DOMAIN)
        drop.update((id(swish), id(expand), id(sigmoid)))
        count += 1
    return [replaced.get(id(n), n) for n in nodes if id(n) not in drop], count


def fuse_means(nodes):
    """GlobalAveragePool of an hkf.DepthwiseConv's output -> that convolution's second output."""
    producers = producers_of(nodes)
    drop, count = set(), 0
    for node in nodes:
        if node.op_type != "GlobalAveragePool":
            continue
        source = producers.get(node.input[0])
        if source is not None and source.op_type == "DepthwiseConv" and len(source.output) == 1:
            source.output.append(node.output[0])
            set_attribute(source, "means", 1)
            drop.add(id(node))
            count += 1
    return [n for n in nodes if id(n) not in drop], count


def rewrite(model):
    weights = {t.name: numpy_helper.to_array(t) for t in model.graph.initializer}
    pixels = plane_pixels(model)
    nodes = list(model.graph.node)
    nodes, swishes = fuse_swish(nodes)
    nodes, counts = fuse_convolutions(nodes, weights, pixels)
    nodes, counts["gates"] = fuse_gates(nodes)
    nodes, counts["residuals"] = fuse_residuals(nodes)
    nodes, counts["means"] = fuse_means(nodes)
    nodes, counts["excitations"] = fuse_excitations(nodes, weights)
    del model.graph.node[:]
    model.graph.node.extend(nodes)
    model.opset_import.append(helper.make_opsetid(DOMAIN, 1))
    return swishes, counts


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("source", help="the converted ONNX graph (not changed)")
    parser.add_argument("target", help="the rewritten graph to write")
    args = parser.parse_args()
    try:
        model = onnx.load(args.source)
        swishes, counts = rewrite(model)
        onnx.checker.check_model(model)
        onnx.save(model, args.target)
    except (OSError, ValueError, onnx.checker.ValidationError) as e:
        print(f"fast_layers: {e}", file=sys.stderr)
        return 1
    print(f"fast_layers: wrote {args.target}: {swishes} swishes, {counts['DepthwiseConv']} depthwise, "
          f"{counts['PointwiseConv']} pointwise and {counts['UnfoldedConv']} unfolded convolutions, {counts['gates']} gates, "
          f"{counts['residuals']} residuals, {counts['means']} means and {counts['excitations']} excitations "
          f"taken in ({len(model.graph.node)} nodes)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
