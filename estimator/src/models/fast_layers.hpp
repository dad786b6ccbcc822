// fast_layers.hpp - the layers hkf gives OpenCV's DNN module, for the networks whose graphs
// dev/models/fast_layers.py rewrites at conversion time (WHENet's EfficientNet-B0):
// - "hkf.Swish": x * sigmoid(x) as one vectorised activation, which OpenCV fuses into the
//   convolution before it (OpenCV 4.6 runs a swish as a scalar Sigmoid layer and a product);
// - "hkf.DepthwiseConv": a depthwise convolution of any square kernel and stride, its
//   (possibly asymmetric) zero padding, bias, an optional swish and the planes' means in one pass
//   (OpenCV 4.6's fast depthwise path takes only 3x3 kernels on planes at least 18 wide; the rest go
//   through im2row one channel at a time, and an asymmetric padding is a layer of its own);
// - "hkf.PointwiseConv": a 1x1 convolution in register tiles, with an optional swish and a
//   squeeze-and-excitation's gate (OpenCV 4.6's runs at about a third of the tile's speed here);
// - "hkf.UnfoldedConv": a dense k x k convolution as the same tiles over its unfolded input (im2col),
//   with its padding and an optional swish (WHENet's first layer: OpenCV's took 1 ms of 16);
// - "hkf.SqueezeExcite": a squeeze-and-excitation's gate from its means in one layer (OpenCV ran two 1x1
//   convolutions and two activations, each a parallel region).
// The network still runs in cv::dnn::Net; these are its layer implementations for five op types.
#pragma once

namespace hkf_estimator {

// Registers the layer types with OpenCV's layer factory (once; safe to call again, from any thread).
void register_fast_layers();

// swish(x) = x / (1 + exp(-x)) over n floats (dst may be src), the activation the layers apply.
void swish_in_place(const float *src, float *dst, long n);

// The mean of n > 0 floats (the depthwise layer's second output, per plane).
float plane_mean(const float *plane, long n);

}  // namespace hkf_estimator
