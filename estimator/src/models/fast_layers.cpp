// fast_layers.cpp - see fast_layers.hpp.
#include "fast_layers.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/dnn.hpp>
#include <opencv2/dnn/all_layers.hpp>
#include <opencv2/dnn/layer.details.hpp>

// The loops below are built for the wider vectors too and the CPU's best taken at load time (GCC's
// function multiversioning); a build for the baseline alone where the compiler cannot.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define HKF_VECTOR_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define HKF_VECTOR_CLONES
#endif

namespace hkf_estimator {

namespace {

// exp(t) for t in [-87, 88] (clamped outside), written so that a compiler vectorises a loop of it: the
// clamp as t + relu(-87 - t) and t - relu(t - 88), relu(d) = (d + |d|) / 2, which leave a t inside
// exactly as it is (a comparison would be a branch GCC does not if-convert); t = k ln2 + r with |r| <= ln2 / 2 (Cody-Waite), exp(r)
// by its Taylor series to r^6 (relative error below 2e-7 there), 2^k by the float's exponent bits; k
// from the round-to-nearest trick (adding 1.5 * 2^23 leaves k in the low mantissa bits), so no
// float-to-int conversion is made.
inline float exp_approx(float t)
{
    const float below = -87.0f - t;
    t += 0.5f * (below + std::fabs(below));  // max(t, -87)
    const float above = t - 88.0f;
    t -= 0.5f * (above + std::fabs(above));  // min(t, 88)
    const float magic = 12582912.0f;  // 1.5 * 2^23
    const float shifted = t * 1.44269504088896341f + magic;
    const float k = shifted - magic;
    const float r = (t - k * 0.693145751953125f) - k * 1.428606765330187e-06f;
    const float p =
        1.0f + r * (1.0f + r * (0.5f + r * (1.0f / 6 + r * (1.0f / 24 + r * (1.0f / 120 + r * (1.0f / 720))))));
    std::uint32_t shifted_bits, p_bits;
    std::memcpy(&shifted_bits, &shifted, sizeof shifted_bits);
    std::memcpy(&p_bits, &p, sizeof p_bits);
    p_bits += (shifted_bits - 0x4B400000u) << 23;  // times 2^k: k added to the exponent
    float out;
    std::memcpy(&out, &p_bits, sizeof out);
    return out;
}

int int_param(const cv::dnn::LayerParams &params, const char *name)
{
    if (!params.has(name)) CV_Error(cv::Error::StsBadArg, std::string("hkf.DepthwiseConv: no attribute ") + name);
    return params.get<int>(name);
}

// "hkf.Swish": an activation, so that OpenCV fuses it into the convolution before it (forwardSlice
// is then called on each stripe of that convolution's output).
class SwishLayer : public cv::dnn::ActivationLayer {
public:
    explicit SwishLayer(const cv::dnn::LayerParams &params) { setParamsFrom(params); }

    static cv::Ptr<cv::dnn::Layer> create(cv::dnn::LayerParams &params) { return cv::makePtr<SwishLayer>(params); }

    bool getMemoryShapes(const std::vector<cv::dnn::MatShape> &inputs, const int required_outputs,
                         std::vector<cv::dnn::MatShape> &outputs,
                         std::vector<cv::dnn::MatShape> &internals) const override
    {
        Layer::getMemoryShapes(inputs, required_outputs, outputs, internals);
        return true;  // in place
    }

    void forward(cv::InputArrayOfArrays inputs_arr, cv::OutputArrayOfArrays outputs_arr,
                 cv::OutputArrayOfArrays) override
    {
        std::vector<cv::Mat> inputs, outputs;
        inputs_arr.getMatVector(inputs);
        outputs_arr.getMatVector(outputs);
        for (size_t i = 0; i < inputs.size(); ++i) {
            CV_Assert(inputs[i].type() == CV_32F && inputs[i].isContinuous() && outputs[i].isContinuous());
            swish_in_place(inputs[i].ptr<float>(), outputs[i].ptr<float>(), static_cast<long>(inputs[i].total()));
        }
    }

    void forwardSlice(const float *src, float *dst, int len, size_t plane_size, int cn0, int cn1) const override
    {
        for (int c = cn0; c < cn1; ++c, src += plane_size, dst += plane_size) swish_in_place(src, dst, len);
    }
};

// "hkf.DepthwiseConv": input N x C x H x W, blobs[0] the kernels C x 1 x k x k, blobs[1] the bias
// (C); attributes kernel, stride, pad_top, pad_left, pad_bottom, pad_right, swish (0 or 1).
class DepthwiseConvLayer : public cv::dnn::Layer {
public:
    explicit DepthwiseConvLayer(const cv::dnn::LayerParams &params)
    {
        setParamsFrom(params);
        kernel_ = int_param(params, "kernel");
        stride_ = int_param(params, "stride");
        pad_top_ = int_param(params, "pad_top");
        pad_left_ = int_param(params, "pad_left");
        pad_bottom_ = int_param(params, "pad_bottom");
        pad_right_ = int_param(params, "pad_right");
        swish_ = params.get<int>("swish", 0) != 0;
        if (kernel_ < 1 || kernel_ > 15 || stride_ < 1 || stride_ > 4 || pad_top_ < 0 || pad_left_ < 0 ||
            pad_bottom_ < 0 || pad_right_ < 0 || pad_top_ >= kernel_ || pad_left_ >= kernel_ ||
            pad_bottom_ >= kernel_ || pad_right_ >= kernel_)
            CV_Error(cv::Error::StsBadArg, "hkf.DepthwiseConv: kernel, stride or padding out of range");
        if (blobs.size() != 2 || blobs[0].dims != 4 || blobs[0].size[1] != 1 || blobs[0].size[2] != kernel_ ||
            blobs[0].size[3] != kernel_ || static_cast<int>(blobs[1].total()) != blobs[0].size[0] ||
            blobs[0].type() != CV_32F || blobs[1].type() != CV_32F)
            CV_Error(cv::Error::StsBadArg, "hkf.DepthwiseConv: wants a C x 1 x k x k kernel and a bias of C");
        blobs[0] = blobs[0].clone();  // continuous, owned
        blobs[1] = blobs[1].clone();
    }

    static cv::Ptr<cv::dnn::Layer> create(cv::dnn::LayerParams &params)
    {
        return cv::makePtr<DepthwiseConvLayer>(params);
    }

    bool getMemoryShapes(const std::vector<cv::dnn::MatShape> &inputs, const int,
                         std::vector<cv::dnn::MatShape> &outputs, std::vector<cv::dnn::MatShape> &) const override
    {
        CV_Assert(inputs.size() == 1 && inputs[0].size() == 4 && inputs[0][1] == blobs[0].size[0]);
        const int padded_h = inputs[0][2] + pad_top_ + pad_bottom_, padded_w = inputs[0][3] + pad_left_ + pad_right_;
        CV_Assert(padded_h >= kernel_ && padded_w >= kernel_);
        outputs.assign(1, cv::dnn::MatShape{inputs[0][0], inputs[0][1], (padded_h - kernel_) / stride_ + 1,
                                            (padded_w - kernel_) / stride_ + 1});
        return false;
    }

    void forward(cv::InputArrayOfArrays inputs_arr, cv::OutputArrayOfArrays outputs_arr,
                 cv::OutputArrayOfArrays) override
    {
        std::vector<cv::Mat> inputs, outputs;
        inputs_arr.getMatVector(inputs);
        outputs_arr.getMatVector(outputs);
        const cv::Mat &in = inputs[0];
        cv::Mat &out = outputs[0];
        CV_Assert(in.type() == CV_32F && in.isContinuous() && out.isContinuous());
        const int planes = in.size[0] * in.size[1];
        cv::parallel_for_(cv::Range(0, planes), [&](const cv::Range &range) {
            std::vector<float> padded, extended;
            for (int p = range.start; p < range.end; ++p) convolve_plane(in, out, p, padded, extended);
        });
    }

private:
    // The extended outputs sum[j], j < count, of a K x K kernel at STRIDE: all K^2 taps of one output
    // summed in registers (one store per output), the loop over j vectorised.
    template <int K, int STRIDE>
    HKF_VECTOR_CLONES static void taps(const float *padded, int pitch, const float *weights, float bias, float *__restrict sum,
                     size_t count)
    {
        float w[K * K];
        std::memcpy(w, weights, sizeof w);
        for (size_t j = 0; j < count; ++j) {
            const float *at = padded + j * STRIDE;
            float acc = bias;
            for (int ky = 0; ky < K; ++ky)
                for (int kx = 0; kx < K; ++kx) acc += w[ky * K + kx] * at[ky * pitch + kx];
            sum[j] = acc;
        }
    }

    // The same for a kernel size or stride without a template above (none in WHENet).
    void any_taps(const float *padded, int pitch, const float *weights, float bias, float *__restrict sum,
                  size_t count) const
    {
        for (size_t j = 0; j < count; ++j) {
            const float *at = padded + j * stride_;
            float acc = bias;
            for (int ky = 0; ky < kernel_; ++ky)
                for (int kx = 0; kx < kernel_; ++kx) acc += weights[ky * kernel_ + kx] * at[ky * pitch + kx];
            sum[j] = acc;
        }
    }

    // One channel's plane: copied into a zero-padded buffer P of row pitch Wp, then each kernel tap
    // (ky, kx) added as one long loop over the "extended" outputs j = oy Wp + ox, ox < Wp, which read
    // P[stride j + ky Wp + kx]: the compiler vectorises it whatever the plane's width (on 7 x 7 planes a
    // loop per output row would be as short as the vector). The columns ox >= the output's width are
    // then dropped; last the bias and the swish.
    void convolve_plane(const cv::Mat &in, cv::Mat &out, int plane, std::vector<float> &padded,
                        std::vector<float> &extended) const
    {
        const int channel = plane % in.size[1];
        const int h = in.size[2], w = in.size[3], out_h = out.size[2], out_w = out.size[3];
        const int pitch = w + pad_left_ + pad_right_;
        const size_t count = static_cast<size_t>(out_h) * pitch;
        padded.assign(stride_ * count + static_cast<size_t>(kernel_) * (pitch + 1), 0.0f);
        const float *src = in.ptr<float>() + static_cast<size_t>(plane) * h * w;
        for (int y = 0; y < h; ++y)
            std::memcpy(&padded[static_cast<size_t>(y + pad_top_) * pitch + pad_left_], src + static_cast<size_t>(y) * w,
                        sizeof(float) * w);
        const float *weights = blobs[0].ptr<float>() + static_cast<size_t>(channel) * kernel_ * kernel_;
        const float bias = blobs[1].ptr<float>()[channel];
        extended.resize(count);
        if (kernel_ == 3 && stride_ == 1) {
            taps<3, 1>(padded.data(), pitch, weights, bias, extended.data(), count);
        } else if (kernel_ == 3 && stride_ == 2) {
            taps<3, 2>(padded.data(), pitch, weights, bias, extended.data(), count);
        } else if (kernel_ == 5 && stride_ == 1) {
            taps<5, 1>(padded.data(), pitch, weights, bias, extended.data(), count);
        } else if (kernel_ == 5 && stride_ == 2) {
            taps<5, 2>(padded.data(), pitch, weights, bias, extended.data(), count);
        } else {
            any_taps(padded.data(), pitch, weights, bias, extended.data(), count);
        }
        const float *sum = extended.data();
        float *dst = out.ptr<float>() + static_cast<size_t>(plane) * out_h * out_w;
        for (int oy = 0; oy < out_h; ++oy)
            std::memcpy(dst + static_cast<size_t>(oy) * out_w, sum + static_cast<size_t>(oy) * pitch, sizeof(float) * out_w);
        if (swish_) swish_in_place(dst, dst, static_cast<long>(out_h) * out_w);
    }

    int kernel_ = 0, stride_ = 1, pad_top_ = 0, pad_left_ = 0, pad_bottom_ = 0, pad_right_ = 0;
    bool swish_ = false;
};

}  // namespace

HKF_VECTOR_CLONES void swish_in_place(const float *src, float *dst, long n)
{
    for (long i = 0; i < n; ++i) {
        const float x = src[i];
        dst[i] = x / (1.0f + exp_approx(-x));
    }
}

void register_fast_layers()
{
    static std::once_flag once;
    std::call_once(once, [] {
        cv::dnn::LayerFactory::registerLayer("hkf.Swish", SwishLayer::create);
        cv::dnn::LayerFactory::registerLayer("hkf.DepthwiseConv", DepthwiseConvLayer::create);
    });
}

}  // namespace hkf_estimator
