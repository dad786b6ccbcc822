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
#include <opencv2/dnn/shape_utils.hpp>

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
// exactly as it is (a comparison would be a branch GCC does not if-convert); t = k ln2 + r with
// |r| <= ln2 / 2 (Cody-Waite), exp(r) by its Taylor series to r^6 (relative error below 2e-7 there),
// 2^k by the float's exponent bits; k from the round-to-nearest trick (adding 1.5 * 2^23 leaves k in
// the low mantissa bits), so no float-to-int conversion is made.
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

// One tile of a 1x1 convolution: kRows output channels x kPixels pixels, summed in 2 * kRows vector
// registers over the input channels (GCC's vector extension: 16 floats, one AVX-512 register, two AVX2
// ones).
constexpr int kRows = 8, kPixels = 32;
typedef float Floats16 __attribute__((vector_size(64)));

struct Tile {
    const float *weights;  // the tile's weights, [cin][kRows]
    int cin;
    const float *in;       // cin rows of in_pitch floats from the tile's first pixel
    long in_pitch;
    const float *bias;     // kRows
    float *out;            // kRows rows of out_pitch floats
    long out_pitch;
};

HKF_VECTOR_CLONES void pointwise_tile(const Tile &t)
{
    Floats16 sum[kRows][2];
    for (int r = 0; r < kRows; ++r) {
        sum[r][0] = Floats16{} + t.bias[r];
        sum[r][1] = sum[r][0];
    }
    for (int c = 0; c < t.cin; ++c) {
        Floats16 x0, x1;
        std::memcpy(&x0, t.in + c * t.in_pitch, sizeof x0);
        std::memcpy(&x1, t.in + c * t.in_pitch + 16, sizeof x1);
        const float *w = t.weights + static_cast<long>(c) * kRows;
        for (int r = 0; r < kRows; ++r) {
            sum[r][0] += x0 * w[r];
            sum[r][1] += x1 * w[r];
        }
    }
    for (int r = 0; r < kRows; ++r) {
        std::memcpy(t.out + r * t.out_pitch, &sum[r][0], sizeof sum[r][0]);
        std::memcpy(t.out + r * t.out_pitch + 16, &sum[r][1], sizeof sum[r][1]);
    }
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
        Tensors t(inputs_arr, outputs_arr);
        for (size_t i = 0; i < t.in.size(); ++i)
            swish_in_place(t.in[i].ptr<float>(), t.out[i].ptr<float>(), static_cast<long>(t.in[i].total()));
    }

    void forwardSlice(const float *src, float *dst, int len, size_t plane_size, int cn0, int cn1) const override
    {
        for (int c = cn0; c < cn1; ++c, src += plane_size, dst += plane_size) swish_in_place(src, dst, len);
    }
};

// "hkf.DepthwiseConv": input N x C x H x W, blobs[0] the kernels C x 1 x k x k, blobs[1] the bias
// (C); attributes kernel, stride, pad_top, pad_left, pad_bottom, pad_right, swish (0 or 1), means (0 or
// 1): with means 1 a second output, each output plane's mean, N x C x 1 x 1 (the global average pooling
// of the squeeze-and-excitation that reads it, taken while the plane is in cache).
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
        means_ = params.get<int>("means", 0) != 0;
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
        if (means_) outputs.push_back(cv::dnn::MatShape{inputs[0][0], inputs[0][1], 1, 1});
        return false;
    }

    void forward(cv::InputArrayOfArrays inputs_arr, cv::OutputArrayOfArrays outputs_arr,
                 cv::OutputArrayOfArrays) override
    {
        Tensors t(inputs_arr, outputs_arr);
        const cv::Mat &in = t.in[0];
        cv::Mat &out = t.out[0];
        const int planes = in.size[0] * in.size[1];
        float *means = means_ && t.out.size() == 2 ? t.out[1].ptr<float>() : nullptr;
        cv::parallel_for_(cv::Range(0, planes), [&](const cv::Range &range) {
            std::vector<float> padded, extended;
            const long plane = static_cast<long>(out.size[2]) * out.size[3];
            for (int p = range.start; p < range.end; ++p) {
                convolve_plane(in, out, p, padded, extended);
                if (means != nullptr) means[p] = plane_mean(out.ptr<float>() + plane * p, plane);
            }
        });
    }

private:
    // The extended outputs sum[j], j < count, of a K x K kernel at STRIDE: all K^2 taps of one output
    // summed in registers (one store per output), the loop over j vectorised.
    template <int K, int STRIDE>
    HKF_VECTOR_CLONES static void taps(const float *padded, int pitch, const float *weights, float bias,
                                       float *__restrict sum, size_t count)
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

    // One channel's plane: copied into a zero-padded buffer P of row pitch Wp, then the bias and all
    // kernel taps summed for each "extended" output j = oy Wp + ox, ox < Wp, which reads
    // P[stride j + ky Wp + kx], in one long loop over j: the compiler vectorises it whatever the plane's
    // width (on 7 x 7 planes a loop per output row would be as short as the vector). The columns
    // ox >= the output's width are then dropped; last the swish.
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
    bool swish_ = false, means_ = false;
};

// "hkf.PointwiseConv": a 1x1 convolution (stride 1, no padding) as a matrix product, tiled as
// pointwise_tile; input N x Cin x H x W, and optionally a second one, a gate N x Cin x 1 x 1 that
// multiplies each input channel first (squeeze-and-excitation's: W (g x) = (W diag g) x, so it scales
// the weights, or the input where that is fewer products); blobs[0] the weights Cout x Cin x 1 x 1,
// blobs[1] the bias (Cout; none: 0); attribute swish (0 or 1). The weights are packed into tiles once,
// when the layer is made. A plane's last pixels, fewer than a tile, are copied into a zero-padded tile.
class PointwiseConvLayer : public cv::dnn::Layer {
public:
    explicit PointwiseConvLayer(const cv::dnn::LayerParams &params)
    {
        setParamsFrom(params);
        swish_ = params.get<int>("swish", 0) != 0;
        if (blobs.empty() || blobs.size() > 2 || blobs[0].dims != 4 || blobs[0].size[2] != 1 || blobs[0].size[3] != 1 ||
            blobs[0].type() != CV_32F || (blobs.size() == 2 && (blobs[1].type() != CV_32F ||
                                                                 static_cast<int>(blobs[1].total()) != blobs[0].size[0])))
            CV_Error(cv::Error::StsBadArg, "hkf.PointwiseConv: wants a Cout x Cin x 1 x 1 kernel and a bias of Cout");
        out_channels_ = blobs[0].size[0];
        in_channels_ = blobs[0].size[1];
        const int tiles = (out_channels_ + kRows - 1) / kRows;
        packed_.assign(static_cast<size_t>(tiles) * in_channels_ * kRows, 0.0f);
        bias_.assign(static_cast<size_t>(tiles) * kRows, 0.0f);
        const cv::Mat weights = blobs[0].isContinuous() ? blobs[0] : blobs[0].clone();
        for (int o = 0; o < out_channels_; ++o) {
            for (int c = 0; c < in_channels_; ++c)
                packed_[(static_cast<size_t>(o / kRows) * in_channels_ + c) * kRows + o % kRows] =
                    weights.ptr<float>()[static_cast<size_t>(o) * in_channels_ + c];
            if (blobs.size() == 2) bias_[o] = blobs[1].ptr<float>()[o];
        }
    }

    static cv::Ptr<cv::dnn::Layer> create(cv::dnn::LayerParams &params)
    {
        return cv::makePtr<PointwiseConvLayer>(params);
    }

    bool getMemoryShapes(const std::vector<cv::dnn::MatShape> &inputs, const int,
                         std::vector<cv::dnn::MatShape> &outputs, std::vector<cv::dnn::MatShape> &) const override
    {
        CV_Assert((inputs.size() == 1 || inputs.size() == 2) && inputs[0].size() == 4 && inputs[0][1] == in_channels_);
        if (inputs.size() == 2)  // the gate: one value per image and input channel
            CV_Assert(inputs[1].size() >= 2 && inputs[1][0] == inputs[0][0] && inputs[1][1] == in_channels_ &&
                      cv::dnn::total(inputs[1]) == inputs[0][0] * in_channels_);
        outputs.assign(1, cv::dnn::MatShape{inputs[0][0], out_channels_, inputs[0][2], inputs[0][3]});
        return false;
    }

    void forward(cv::InputArrayOfArrays inputs_arr, cv::OutputArrayOfArrays outputs_arr,
                 cv::OutputArrayOfArrays) override
    {
        Tensors t(inputs_arr, outputs_arr);
        const cv::Mat &in = t.in[0];
        cv::Mat &out = t.out[0];
        const int pixels = in.size[2] * in.size[3], batch = in.size[0];
        const int pixel_tiles = (pixels + kPixels - 1) / kPixels, row_tiles = (out_channels_ + kRows - 1) / kRows;
        // tasks: every pixel tile, its output rows split so that there are at least 8 tasks to share
        const int groups = std::min(row_tiles, std::max(1, (8 + pixel_tiles - 1) / pixel_tiles));
        const int rows_per_group = (row_tiles + groups - 1) / groups;
        for (int image = 0; image < batch; ++image) {
            Image m{packed_.data(), in.ptr<float>() + static_cast<size_t>(image) * in_channels_ * pixels,
                    out.ptr<float>() + static_cast<size_t>(image) * out_channels_ * pixels, pixels};
            if (t.in.size() == 2) apply_gate(t.in[1].ptr<float>() + static_cast<size_t>(image) * in_channels_, &m);
            cv::parallel_for_(cv::Range(0, pixel_tiles * groups), [&](const cv::Range &range) {
                std::vector<float> tail;
                for (int task = range.start; task < range.end; ++task) {
                    const int first_row_tile = task % groups * rows_per_group;
                    multiply_tiles(m, task / groups * kPixels, first_row_tile,
                                   std::min(row_tiles, first_row_tile + rows_per_group), tail);
                }
            });
        }
    }

private:
    // One image's product: the packed weights, its input and output planes of `pixels` floats.
    struct Image {
        const float *weights, *src;
        float *dst;
        int pixels;
    };

    // The gate g (Cin values) applied: to a copy of the weights (Cout x Cin products) or of the input
    // (Cin x pixels), whichever is fewer; m's weights or src then point at the copy.
    void apply_gate(const float *gate, Image *m)
    {
        const int pixels = m->pixels;
        if (static_cast<long>(pixels) <= out_channels_) {
            gated_.resize(static_cast<size_t>(in_channels_) * pixels);
            for (int c = 0; c < in_channels_; ++c)
                for (int i = 0; i < pixels; ++i)
                    gated_[static_cast<size_t>(c) * pixels + i] = m->src[static_cast<size_t>(c) * pixels + i] * gate[c];
            m->src = gated_.data();
        } else {
            gated_.resize(packed_.size());
            const size_t tiles = packed_.size() / (static_cast<size_t>(in_channels_) * kRows);
            for (size_t i = 0; i < tiles * in_channels_; ++i)  // [tile][Cin][kRows]: row i's input channel i % Cin
                for (int r = 0; r < kRows; ++r) gated_[i * kRows + r] = packed_[i * kRows + r] * gate[i % in_channels_];
            m->weights = gated_.data();
        }
    }

    // The output rows of tiles [first, last) at the pixels from `pixel` (a tile's, or what is left).
    void multiply_tiles(const Image &m, int pixel, int first, int last, std::vector<float> &tail) const
    {
        const int pixels = m.pixels, count = std::min(kPixels, pixels - pixel);
        const float *tile_in = m.src + pixel;
        long pitch = pixels;
        if (count < kPixels) {
            tail.assign(static_cast<size_t>(in_channels_) * kPixels, 0.0f);
            for (int c = 0; c < in_channels_; ++c)
                std::memcpy(&tail[static_cast<size_t>(c) * kPixels], m.src + static_cast<size_t>(c) * pixels + pixel,
                            sizeof(float) * count);
            tile_in = tail.data();
            pitch = kPixels;
        }
        float scratch[kRows * kPixels];
        for (int t = first; t < last; ++t) {
            const int rows = std::min(kRows, out_channels_ - t * kRows);
            float *tile_out = m.dst + static_cast<size_t>(t) * kRows * pixels + pixel;
            const float *weights = m.weights + static_cast<size_t>(t) * in_channels_ * kRows;
            if (count == kPixels && rows == kRows) {
                pointwise_tile(Tile{weights, in_channels_, tile_in, pitch, &bias_[t * kRows], tile_out, pixels});
            } else {
                pointwise_tile(Tile{weights, in_channels_, tile_in, pitch, &bias_[t * kRows], scratch, kPixels});
                for (int r = 0; r < rows; ++r)
                    std::memcpy(tile_out + static_cast<size_t>(r) * pixels, scratch + r * kPixels, sizeof(float) * count);
            }
            if (swish_)
                for (int r = 0; r < rows; ++r)
                    swish_in_place(tile_out + static_cast<size_t>(r) * pixels, tile_out + static_cast<size_t>(r) * pixels,
                                   count);
        }
    }

    int out_channels_ = 0, in_channels_ = 0;
    bool swish_ = false;
    std::vector<float> packed_, bias_;  // weights as [tile][Cin][kRows]; the bias padded to whole tiles
    std::vector<float> gated_;          // the gated weights or input of the image being run
};

}  // namespace

// The mean of n floats: 16 running sums (a loop the compiler vectorises; one sum would be a chain of
// dependent additions), added in double at the end.
HKF_VECTOR_CLONES float plane_mean(const float *plane, long n)
{
    float partial[16] = {};
    long i = 0;
    for (; i + 16 <= n; i += 16)
        for (int k = 0; k < 16; ++k) partial[k] += plane[i + k];
    double sum = 0.0;
    for (; i < n; ++i) sum += plane[i];
    for (int k = 0; k < 16; ++k) sum += partial[k];
    return static_cast<float>(sum / static_cast<double>(n));
}

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
        cv::dnn::LayerFactory::registerLayer("hkf.PointwiseConv", PointwiseConvLayer::create);
    });
}

}  // namespace hkf_estimator
