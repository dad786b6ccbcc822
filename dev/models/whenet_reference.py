"""WHENet run straight from its Keras weights with NumPy, in Keras's own terms:
NHWC tensors, unfused batch norm, TensorFlow 'same' padding computed per
layer, dense layers as x @ W + b. It shares no graph code with
convert_whenet.py (only the EfficientNet-B0 block table), so comparing the two
checks the ONNX mechanics: batch-norm folding, padding, layouts, Gemm.
"""
import h5py
import numpy as np

from convert_whenet import B0_STAGES, BN_EPSILON, STEM_FILTERS


class KerasWeights:
    def __init__(self, path):
        f = h5py.File(path, "r")
        names = [n.decode() for n in f.attrs["layer_names"]]
        self.groups = [f[n] for n in names if len(f[n].attrs["weight_names"]) > 0]
        self.i = 0

    def take(self):
        g = self.groups[self.i]
        self.i += 1
        return [np.array(g[w], dtype=np.float64) for w in g.attrs["weight_names"]]


def pad_same(x, k, s):
    """Zero padding of an NHWC tensor as TensorFlow's 'same' does it."""
    h = x.shape[1]
    out = -(-h // s)
    total = max((out - 1) * s + k - h, 0)
    before, after = total // 2, total - total // 2
    return np.pad(x, ((0, 0), (before, after), (before, after), (0, 0))), out


def conv(x, kernel, stride, bias=None):
    k = kernel.shape[0]
    xp, out = pad_same(x, k, stride)
    y = np.zeros((x.shape[0], out, out, kernel.shape[3]))
    for i in range(k):
        for j in range(k):
            patch = xp[:, i:i + stride * out:stride, j:j + stride * out:stride, :]
            y += patch @ kernel[i, j]
    return y if bias is None else y + bias


def depthwise(x, kernel, stride):
    k = kernel.shape[0]
    xp, out = pad_same(x, k, stride)
    y = np.zeros((x.shape[0], out, out, x.shape[3]))
    for i in range(k):
        for j in range(k):
            y += xp[:, i:i + stride * out:stride, j:j + stride * out:stride, :] * kernel[i, j, :, 0]
    return y


def batch_norm(x, weights):
    gamma, beta, mean, variance = weights
    return (x - mean) / np.sqrt(variance + BN_EPSILON) * gamma + beta


def swish(x):
    return x / (1.0 + np.exp(-x))


def whenet_logits(h5_path, image_nhwc):
    """Yaw, pitch and roll logits for a normalised NHWC float image batch."""
    w = KerasWeights(h5_path)
    x = swish(batch_norm(conv(image_nhwc, w.take()[0], 2), w.take()))
    filters = STEM_FILTERS
    for kernel, stride, expand, out_filters, repeats in B0_STAGES:
        for r in range(repeats):
            s = stride if r == 0 else 1
            inputs = x
            if expand != 1:
                x = swish(batch_norm(conv(x, w.take()[0], 1), w.take()))
            x = swish(batch_norm(depthwise(x, w.take()[0], s), w.take()))
            k1, b1 = w.take()
            k2, b2 = w.take()
            squeeze = x.mean(axis=(1, 2), keepdims=True)
            gate = 1.0 / (1.0 + np.exp(-conv(swish(conv(squeeze, k1, 1, b1)), k2, 1, b2)))
            x = batch_norm(conv(x * gate, w.take()[0], 1), w.take())
            if s == 1 and filters == out_filters:
                x = x + inputs
            filters = out_filters
    x = swish(batch_norm(conv(x, w.take()[0], 1), w.take()))
    features = x.mean(axis=(1, 2))
    return [features @ kernel + bias for kernel, bias in (w.take(), w.take(), w.take())]


def decode(logits, step, offset):
    e = np.exp(logits - logits.max())
    p = e / e.sum()
    return float((p * np.arange(len(logits))).sum() * step + offset)
