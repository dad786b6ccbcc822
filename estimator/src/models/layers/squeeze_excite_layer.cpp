// squeeze_excite_layer.cpp - "hkf.SqueezeExcite" (see fast_layers.hpp).
#include <algorithm>
#include <cstring>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>
#include <opencv2/dnn/all_layers.hpp>
#include <opencv2/dnn/shape_utils.hpp>

#include "layer_support.hpp"
#include "simd_level.hpp"

namespace hkf_estimator {

namespace {

// "hkf.SqueezeExcite": a squeeze-and-excitation's gate from its means, g = sigmoid(W2 swish(W1 m + b1) + b2);
// input N x C x 1 x 1 (the means), blobs W1 (R x C x 1 x 1), b1 (R), W2 (C x R x 1 x 1), b2 (C); output
// N x C x 1 x 1. Thousands of products per image: the level's loops (LayerKernels::accumulate_rows, swish,
// sigmoid), on two threads only for the largest (kSplitProducts; OpenCV ran it as two 1x1 convolutions and two
// activations, each with a parallel region of its own).
class SqueezeExciteLayer : public cv::dnn::Layer {
public:
    explicit SqueezeExciteLayer(const cv::dnn::LayerParams &params) : kernels_(layer_kernels_in_use())
    {
        setParamsFrom(params);
        for (cv::Mat &b : blobs) b = b.clone();  // continuous, owned
        const bool shaped = blobs.size() == 4 && blobs[0].dims == 4 && blobs[2].dims == 4 && blobs[0].size[2] == 1 &&
                            blobs[0].size[3] == 1 && blobs[2].size[2] == 1 && blobs[2].size[3] == 1;
        if (!shaped || blobs[0].size[0] != blobs[2].size[1] || blobs[0].size[1] != blobs[2].size[0] ||
            static_cast<int>(blobs[1].total()) != blobs[0].size[0] || static_cast<int>(blobs[3].total()) != blobs[2].size[0] ||
            std::any_of(blobs.begin(), blobs.end(), [](const cv::Mat &b) { return b.type() != CV_32F; }))
            CV_Error(cv::Error::StsBadArg, "hkf.SqueezeExcite: wants W1 R x C x 1 x 1, b1 of R, W2 C x R x 1 x 1, b2 of C");
        reduced_ = blobs[0].size[0];
        channels_ = blobs[0].size[1];
        // transposed, so that each product is a loop of independent sums the compiler vectorises
        // (a dot product's one running sum is a chain it may not reorder)
        w1_by_channel_.resize(static_cast<size_t>(channels_) * reduced_);
        w2_by_reduced_.resize(static_cast<size_t>(reduced_) * channels_);
        for (int r = 0; r < reduced_; ++r)
            for (int c = 0; c < channels_; ++c) {
                w1_by_channel_[static_cast<size_t>(c) * reduced_ + r] = blobs[0].ptr<float>()[static_cast<size_t>(r) * channels_ + c];
                w2_by_reduced_[static_cast<size_t>(r) * channels_ + c] = blobs[2].ptr<float>()[static_cast<size_t>(c) * reduced_ + r];
            }
    }


    bool getMemoryShapes(const std::vector<cv::dnn::MatShape> &inputs, const int,
                         std::vector<cv::dnn::MatShape> &outputs, std::vector<cv::dnn::MatShape> &) const override
    {
        CV_Assert(inputs.size() == 1 && inputs[0].size() >= 2 && inputs[0][1] == channels_ &&
                  cv::dnn::total(inputs[0]) == inputs[0][0] * channels_);
        outputs.assign(1, inputs[0]);
        return false;
    }

    void forward(cv::InputArrayOfArrays inputs_arr, cv::OutputArrayOfArrays outputs_arr,
                 cv::OutputArrayOfArrays) override
    {
        Tensors t(inputs_arr, outputs_arr);
        const float *b1 = blobs[1].ptr<float>(), *b2 = blobs[3].ptr<float>();
        const int parts = static_cast<long>(channels_) * reduced_ >= kSplitProducts ? 2 : 1;
        std::vector<float> hidden(static_cast<size_t>(reduced_) * parts);
        for (int image = 0; image < t.in[0].size[0]; ++image) {
            const float *m = t.in[0].ptr<float>() + static_cast<size_t>(image) * channels_;
            float *g = t.out[0].ptr<float>() + static_cast<size_t>(image) * channels_;
            std::fill(hidden.begin(), hidden.end(), 0.0f);
            cv::parallel_for_(cv::Range(0, parts), [&](const cv::Range &range) {
                for (int part = range.start; part < range.end; ++part) {
                    const int first = channels_ * part / parts, end = channels_ * (part + 1) / parts;
                    kernels_.accumulate_rows(w1_by_channel_.data() + static_cast<size_t>(first) * reduced_, reduced_, m + first,
                                             end - first, reduced_, hidden.data() + static_cast<size_t>(part) * reduced_);
                }
            }, parts);
            for (int r = 0; r < reduced_; ++r) {  // the bias and the other parts' sums into the first's
                float rest = b1[r];
                for (int part = 1; part < parts; ++part) rest += hidden[static_cast<size_t>(part) * reduced_ + r];
                hidden[r] += rest;
            }
            kernels_.swish(hidden.data(), hidden.data(), reduced_);
            std::copy(b2, b2 + channels_, g);
            cv::parallel_for_(cv::Range(0, parts), [&](const cv::Range &range) {
                for (int part = range.start; part < range.end; ++part) {
                    const int first = channels_ * part / parts, end = channels_ * (part + 1) / parts;
                    kernels_.accumulate_rows(w2_by_reduced_.data() + first, channels_, hidden.data(), reduced_, end - first, g + first);
                    kernels_.sigmoid(g + first, g + first, end - first);
                }
            }, parts);
        }
    }

private:
    // From this many weights in each product (WHENet's 1152 x 48 and 672 x 28), each product in two halves, one a
    // thread: the first's rows (two partial sums, then added), the second's columns. The weights come from the
    // last-level cache, so a second core's share of them is what it saves (Intel Xeon, AVX-512, two threads: the 16
    // layers 0.27-0.31 -> 0.23-0.24 ms; split from 9,600 weights alike, from 2,000 0.24-0.26).
    static constexpr long kSplitProducts = 16 * 1024;

    const LayerKernels &kernels_;  // the level in use when the layer was made
    int reduced_ = 0, channels_ = 0;
    std::vector<float> w1_by_channel_, w2_by_reduced_;  // W1 as C x R, W2 as R x C
};

}  // namespace

cv::Ptr<cv::dnn::Layer> make_squeeze_excite_layer(cv::dnn::LayerParams &params) { return cv::makePtr<SqueezeExciteLayer>(params); }

}  // namespace hkf_estimator
