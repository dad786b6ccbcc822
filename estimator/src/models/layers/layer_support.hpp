// layer_support.hpp - what the estimator's own layers (this folder) share: reading an attribute, the
// tensors a forward gets, the strided copies, and a function that makes each layer for OpenCV's layer
// factory (fast_layers.cpp registers them).
#pragma once

#include <algorithm>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>
#include <opencv2/dnn/shape_utils.hpp>

namespace hkf_estimator {

// An integer attribute the layer must have (an error naming the layer's type when it is missing).
inline int int_param(const cv::dnn::LayerParams &params, const char *name)
{
    if (!params.has(name)) CV_Error(cv::Error::StsBadArg, params.type + ": no attribute " + name);
    return params.get<int>(name);
}

// The tensors a layer's forward gets, each float and continuous (as OpenCV allocates them).
struct Tensors {
    std::vector<cv::Mat> in, out;
    Tensors(cv::InputArrayOfArrays inputs, cv::OutputArrayOfArrays outputs)
    {
        inputs.getMatVector(in);
        outputs.getMatVector(out);
        for (const cv::Mat &m : in) CV_Assert(m.type() == CV_32F && m.isContinuous());
        for (const cv::Mat &m : out) CV_Assert(m.type() == CV_32F && m.isContinuous());
    }
};

// dst[i] = src[2 i], i < n: with the stride known, a loop the compiler vectorises.
inline void every_second(const float *__restrict src, float *__restrict dst, int n)
{
    for (int i = 0; i < n; ++i) dst[i] = src[2 * i];
}

// body(range) over the tasks [0, tasks) on OpenCV's threads, in four stripes a thread: with more than one thread,
// OpenCV's default calls the body once per task, and each call makes its buffers anew (the depthwise layer's
// padded planes, zeroed) and takes the pool's lock; four a thread leave room to even out unequal tasks.
template <typename Body>
void parallel_tasks(int tasks, const Body &body)
{
    const double stripes = std::min(static_cast<double>(tasks), 4.0 * std::max(1, cv::getNumThreads()));
    cv::parallel_for_(cv::Range(0, tasks), body, stripes);
}

// The columns c in [0, count) whose input column c stride + offset lies in [0, w): [*first, *end)
// (empty: *first == *end). A padded convolution's copies (the depthwise phases, the unfolded rows).
inline void columns_inside(int offset, int w, int stride, int count, int *first, int *end)
{
    *first = offset >= 0 ? 0 : std::min(count, (-offset + stride - 1) / stride);
    const int last = w - 1 - offset;  // over stride: the last such c, if >= 0
    *end = last < 0 ? *first : std::max(*first, std::min(count, last / stride + 1));
}

// A convolution's window: a square kernel, one stride, a zero padding on each side (the attributes kernel,
// stride, pad_top, pad_left, pad_bottom, pad_right of hkf.DepthwiseConv and hkf.UnfoldedConv).
struct ConvWindow {
    int kernel = 1, stride = 1, top = 0, left = 0, bottom = 0, right = 0;

    // From the layer's attributes; refused (naming the layer's type) out of range, or with a padding as
    // wide as the kernel (outputs of padding alone).
    static ConvWindow read(const cv::dnn::LayerParams &params)
    {
        const ConvWindow w{int_param(params, "kernel"),   int_param(params, "stride"),     int_param(params, "pad_top"),
                           int_param(params, "pad_left"), int_param(params, "pad_bottom"), int_param(params, "pad_right")};
        if (w.kernel < 1 || w.kernel > 15 || w.stride < 1 || w.stride > 4 || std::min({w.top, w.left, w.bottom, w.right}) < 0 ||
            std::max({w.top, w.left, w.bottom, w.right}) >= w.kernel)
            CV_Error(cv::Error::StsBadArg, params.type + ": kernel, stride or padding out of range");
        return w;
    }

    // The output of an N x C x H x W input: N x channels x out_h x out_w.
    cv::dnn::MatShape output_shape(const cv::dnn::MatShape &input, int channels) const
    {
        const int padded_h = input[2] + top + bottom, padded_w = input[3] + left + right;
        CV_Assert(padded_h >= kernel && padded_w >= kernel);
        return cv::dnn::MatShape{input[0], channels, (padded_h - kernel) / stride + 1, (padded_w - kernel) / stride + 1};
    }
};

cv::Ptr<cv::dnn::Layer> make_swish_layer(cv::dnn::LayerParams &params);
cv::Ptr<cv::dnn::Layer> make_depthwise_conv_layer(cv::dnn::LayerParams &params);
cv::Ptr<cv::dnn::Layer> make_pointwise_conv_layer(cv::dnn::LayerParams &params);  // and hkf.UnfoldedConv
cv::Ptr<cv::dnn::Layer> make_squeeze_excite_layer(cv::dnn::LayerParams &params);

}  // namespace hkf_estimator
