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

#include "simd_level.hpp"

namespace hkf_estimator {

namespace {

int int_param(const cv::dnn::LayerParams &params, const char *name)
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

// "hkf.Swish": an activation, so that OpenCV fuses it into the convolution before it (forwardSlice
// is then called on each stripe of that convolution's output).
class SwishLayer : public cv::dnn::ActivationLayer {
public:
    explicit SwishLayer(const cv::dnn::LayerParams &params) : kernels_(layer_kernels_in_use())
    {
        setParamsFrom(params);
    }

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
            kernels_.swish(t.in[i].ptr<float>(), t.out[i].ptr<float>(), static_cast<long>(t.in[i].total()));
    }

    void forwardSlice(const float *src, float *dst, int len, size_t plane_size, int cn0, int cn1) const override
    {
        for (int c = cn0; c < cn1; ++c, src += plane_size, dst += plane_size) kernels_.swish(src, dst, len);
    }

private:
    const LayerKernels &kernels_;  // the level in use when the layer was made
};

// dst[i] = src[2 i], i < n: with the stride known, a loop the compiler vectorises.
void every_second(const float *__restrict src, float *__restrict dst, int n)
{
    for (int i = 0; i < n; ++i) dst[i] = src[2 * i];
}

// "hkf.DepthwiseConv": input N x C x H x W, blobs[0] the kernels C x 1 x k x k, blobs[1] the bias
// (C); attributes kernel, stride, pad_top, pad_left, pad_bottom, pad_right, swish (0 or 1), means (0 or
// 1): with means 1 a second output, each output plane's mean, N x C x 1 x 1 (the global average pooling
// of the squeeze-and-excitation that reads it, taken while the plane is in cache).
class DepthwiseConvLayer : public cv::dnn::Layer {
public:
    explicit DepthwiseConvLayer(const cv::dnn::LayerParams &params) : kernels_(layer_kernels_in_use())
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
        const Phases shape = phases_of(in.size[3], out.size[2]);
        cv::parallel_for_(cv::Range(0, planes), [&](const cv::Range &range) {
            // zeroed once: each plane then writes the input's places only, the padding's stay zero
            std::vector<float> phases(static_cast<size_t>(stride_) * stride_ * shape.size, 0.0f), extended(shape.count);
            const long plane = static_cast<long>(out.size[2]) * out.size[3];
            for (int p = range.start; p < range.end; ++p) {
                convolve_plane(in, out, p, shape, phases.data(), extended.data());
                if (means != nullptr) means[p] = kernels_.plane_mean(out.ptr<float>() + plane * p, plane);
            }
        });
    }

private:
    // The zero-padded plane P (the input with pad_top rows above it, pad_left columns before it) split into
    // stride^2 phases: phase (py, px) holds P[r stride + py][c stride + px] at r pitch + c, pitch =
    // ceil(padded width / stride), `rows` rows (the last tap's, and one for the columns beyond the
    // output's), zero beyond P; `count` extended outputs (convolve_plane). At stride 1 the phase is P.
    struct Phases {
        int pitch, rows;
        long size;     // floats in one phase
        size_t count;  // out_h pitch
    };

    Phases phases_of(int in_w, int out_h) const
    {
        const int pitch = (in_w + pad_left_ + pad_right_ + stride_ - 1) / stride_;
        const int rows = out_h + (kernel_ - 1) / stride_ + 1;
        return Phases{pitch, rows, static_cast<long>(pitch) * rows, static_cast<size_t>(out_h) * pitch};
    }

    // The input plane's floats written to their places in the phases (whose padding is zero already).
    void split_into_phases(const float *src, int h, int w, const Phases &shape, float *phases) const
    {
        for (int px = 0; px < stride_; ++px) {
            // the columns c whose input column x = c stride + px - pad_left is inside [0, w)
            const int first = std::min(shape.pitch, (pad_left_ - px + stride_ - 1) / stride_);
            const int last = w - 1 + pad_left_ - px;  // over stride: the last such c, if >= 0
            const int end = last < 0 ? first : std::max(first, std::min(shape.pitch, last / stride_ + 1));
            for (int py = 0; py < stride_; ++py) {
                float *dst = phases + (py * stride_ + px) * shape.size + first;
                for (int r = 0; r < shape.rows; ++r, dst += shape.pitch) {
                    const int y = r * stride_ + py - pad_top_;  // the input's row
                    if (y < 0 || y >= h) continue;
                    const float *row = src + static_cast<long>(y) * w + first * stride_ + px - pad_left_;
                    if (stride_ == 1)
                        std::memcpy(dst, row, sizeof(float) * (end - first));
                    else if (stride_ == 2)
                        every_second(row, dst, end - first);
                    else
                        for (int c = 0; c < end - first; ++c) dst[c] = row[c * stride_];
                }
            }
        }
    }

    // The extended outputs for a kernel size or stride without a loop of the level's own (none in WHENet):
    // as LayerKernels' taps.
    void any_taps(const PhasePlanes &in, const float *weights, float bias, float *__restrict sum, size_t count) const
    {
        for (size_t j = 0; j < count; ++j) {
            float acc = bias;
            for (int ky = 0; ky < kernel_; ++ky)
                for (int kx = 0; kx < kernel_; ++kx)
                    acc += weights[ky * kernel_ + kx] * in.phases[((ky % stride_) * stride_ + kx % stride_) * in.size +
                                                                  (ky / stride_) * in.pitch + kx / stride_ + j];
            sum[j] = acc;
        }
    }

    // One channel's plane: split into phases (above), then the bias and all kernel taps summed for each
    // "extended" output j = oy pitch + ox, ox < pitch, which reads the phase of (ky, kx) at
    // j + (ky / stride) pitch + kx / stride, in one long loop over j: the compiler vectorises it whatever
    // the plane's width (on 7 x 7 planes a loop per output row would be as short as the vector), with
    // contiguous loads at any stride. The columns ox >= the output's width are then dropped; last the swish.
    void convolve_plane(const cv::Mat &in, cv::Mat &out, int plane, const Phases &shape, float *phases,
                        float *extended) const
    {
        const int channel = plane % in.size[1];
        const int h = in.size[2], w = in.size[3], out_h = out.size[2], out_w = out.size[3];
        split_into_phases(in.ptr<float>() + static_cast<size_t>(plane) * h * w, h, w, shape, phases);
        const float *weights = blobs[0].ptr<float>() + static_cast<size_t>(channel) * kernel_ * kernel_;
        const float bias = blobs[1].ptr<float>()[channel];
        DepthwiseTaps *taps = kernel_ == 3 && stride_ == 1   ? kernels_.taps_3x3_stride1
                              : kernel_ == 3 && stride_ == 2 ? kernels_.taps_3x3_stride2
                              : kernel_ == 5 && stride_ == 1 ? kernels_.taps_5x5_stride1
                              : kernel_ == 5 && stride_ == 2 ? kernels_.taps_5x5_stride2
                                                             : nullptr;
        const PhasePlanes planes{phases, shape.size, shape.pitch};
        if (taps != nullptr)
            taps(planes, weights, bias, extended, shape.count);
        else
            any_taps(planes, weights, bias, extended, shape.count);
        float *dst = out.ptr<float>() + static_cast<size_t>(plane) * out_h * out_w;
        for (int oy = 0; oy < out_h; ++oy)
            std::memcpy(dst + static_cast<size_t>(oy) * out_w, extended + static_cast<size_t>(oy) * shape.pitch,
                        sizeof(float) * out_w);
        if (swish_) kernels_.swish(dst, dst, static_cast<long>(out_h) * out_w);
    }

    const LayerKernels &kernels_;  // the level in use when the layer was made
    int kernel_ = 0, stride_ = 1, pad_top_ = 0, pad_left_ = 0, pad_bottom_ = 0, pad_right_ = 0;
    bool swish_ = false, means_ = false;
};

constexpr int kLargestTile = 256;  // floats in the largest level's pointwise tile (8 x 32)

// "hkf.PointwiseConv": a 1x1 convolution (stride 1, no padding) as a matrix product in the level's
// tiles (LayerKernels::pointwise_tile); input N x Cin x H x W, and optionally a second one, a gate N x Cin x 1 x 1 that
// multiplies each input channel first (squeeze-and-excitation's: W (g x) = (W diag g) x, so it scales
// the weights, or the input where that is fewer products); blobs[0] the weights Cout x Cin x 1 x 1,
// blobs[1] the bias (Cout; none: 0); attribute swish (0 or 1). The weights are packed into tiles once,
// when the layer is made, for the tile of the level in use. A plane's last pixels, fewer than a tile, are
// copied into a zero-padded tile.
// "hkf.UnfoldedConv": a k x k convolution (attributes kernel, stride, pad_top, pad_left, pad_bottom,
// pad_right, as hkf.DepthwiseConv's; blobs[0] Cout x Cin x k x k) as the same product over its unfolded
// input, Cin k^2 rows of the output's pixels (im2col), made for each image; no gate (WHENet's first
// convolution, 3 -> 32 channels at stride 2, which OpenCV 4.6 runs at a third of the tile's speed).

class PointwiseConvLayer : public cv::dnn::Layer {
public:
    explicit PointwiseConvLayer(const cv::dnn::LayerParams &params)
        : kernels_(layer_kernels_in_use()), rows_(kernels_.tile_rows), pixels_(kernels_.tile_pixels)
    {
        setParamsFrom(params);
        swish_ = params.get<int>("swish", 0) != 0;
        read_unfolding(params);
        const int k = unfold_.kernel;
        if (blobs.empty() || blobs.size() > 2 || blobs[0].dims != 4 || blobs[0].size[2] != k || blobs[0].size[3] != k ||
            blobs[0].type() != CV_32F || (blobs.size() == 2 && (blobs[1].type() != CV_32F ||
                                                                 static_cast<int>(blobs[1].total()) != blobs[0].size[0])))
            CV_Error(cv::Error::StsBadArg, "hkf.PointwiseConv: wants a Cout x Cin x k x k kernel (k = 1 unless "
                                           "unfolded) and a bias of Cout");
        CV_Assert(rows_ * pixels_ <= kLargestTile);
        out_channels_ = blobs[0].size[0];
        image_channels_ = blobs[0].size[1];
        in_channels_ = image_channels_ * k * k;  // the rows of the product's input: (c, ky, kx) when unfolded
        const int tiles = (out_channels_ + rows_ - 1) / rows_;
        packed_.assign(static_cast<size_t>(tiles) * in_channels_ * rows_, 0.0f);
        bias_.assign(static_cast<size_t>(tiles) * rows_, 0.0f);
        const cv::Mat weights = blobs[0].isContinuous() ? blobs[0] : blobs[0].clone();
        for (int o = 0; o < out_channels_; ++o) {
            for (int c = 0; c < in_channels_; ++c)
                packed_[(static_cast<size_t>(o / rows_) * in_channels_ + c) * rows_ + o % rows_] =
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
        CV_Assert((inputs.size() == 1 || inputs.size() == 2) && inputs[0].size() == 4 && inputs[0][1] == image_channels_);
        if (inputs.size() == 2)  // the gate: one value per image and input channel
            CV_Assert(unfold_.kernel == 1 && inputs[1].size() >= 2 && inputs[1][0] == inputs[0][0] &&
                      inputs[1][1] == in_channels_ && cv::dnn::total(inputs[1]) == inputs[0][0] * in_channels_);
        const int padded_h = inputs[0][2] + unfold_.top + unfold_.bottom, padded_w = inputs[0][3] + unfold_.left + unfold_.right;
        CV_Assert(padded_h >= unfold_.kernel && padded_w >= unfold_.kernel);
        outputs.assign(1, cv::dnn::MatShape{inputs[0][0], out_channels_, (padded_h - unfold_.kernel) / unfold_.stride + 1,
                                            (padded_w - unfold_.kernel) / unfold_.stride + 1});
        return false;
    }

    void forward(cv::InputArrayOfArrays inputs_arr, cv::OutputArrayOfArrays outputs_arr,
                 cv::OutputArrayOfArrays) override
    {
        Tensors t(inputs_arr, outputs_arr);
        const cv::Mat &in = t.in[0];
        cv::Mat &out = t.out[0];
        const int pixels = out.size[2] * out.size[3], batch = in.size[0];
        const int pixel_tiles = (pixels + pixels_ - 1) / pixels_, row_tiles = (out_channels_ + rows_ - 1) / rows_;
        // tasks: every pixel tile, its output rows split so that there are at least 8 tasks to share
        const int groups = std::min(row_tiles, std::max(1, (8 + pixel_tiles - 1) / pixel_tiles));
        const int rows_per_group = (row_tiles + groups - 1) / groups;
        for (int image = 0; image < batch; ++image) {
            const float *src = in.ptr<float>() + static_cast<size_t>(image) * image_channels_ * in.size[2] * in.size[3];
            if (unfold_.kernel > 1) src = unfold(src, in.size[2], in.size[3], out.size[2], out.size[3]);
            Image m{packed_.data(), src, out.ptr<float>() + static_cast<size_t>(image) * out_channels_ * pixels, pixels};
            if (t.in.size() == 2) apply_gate(t.in[1].ptr<float>() + static_cast<size_t>(image) * in_channels_, &m);
            cv::parallel_for_(cv::Range(0, pixel_tiles * groups), [&](const cv::Range &range) {
                std::vector<float> tail;
                for (int task = range.start; task < range.end; ++task) {
                    const int first_row_tile = task % groups * rows_per_group;
                    multiply_tiles(m, task / groups * pixels_, first_row_tile,
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

    // hkf.UnfoldedConv's attributes (hkf.PointwiseConv: kernel 1, stride 1, no padding).
    void read_unfolding(const cv::dnn::LayerParams &params)
    {
        if (params.type != "hkf.UnfoldedConv") return;
        unfold_ = Unfolding{int_param(params, "kernel"), int_param(params, "stride"), int_param(params, "pad_top"),
                            int_param(params, "pad_left"), int_param(params, "pad_bottom"), int_param(params, "pad_right")};
        const Unfolding &u = unfold_;
        if (u.kernel < 1 || u.kernel > 15 || u.stride < 1 || u.stride > 4 || std::min({u.top, u.left, u.bottom, u.right}) < 0 ||
            std::max({u.top, u.left, u.bottom, u.right}) >= u.kernel)
            CV_Error(cv::Error::StsBadArg, "hkf.UnfoldedConv: kernel, stride or padding out of range");
    }

    // One image's input unfolded into unfolded_: row (c, ky, kx) holds, at output pixel (oy, ox), the input
    // at (oy stride + ky - pad_top, ox stride + kx - pad_left), zero outside it. Returns the rows.
    const float *unfold(const float *src, int h, int w, int out_h, int out_w)
    {
        const Unfolding u = unfold_;
        const long out_pixels = static_cast<long>(out_h) * out_w;
        unfolded_.assign(static_cast<size_t>(in_channels_) * out_pixels, 0.0f);
        cv::parallel_for_(cv::Range(0, in_channels_), [&](const cv::Range &range) {
            for (int row = range.start; row < range.end; ++row) {
                const int c = row / (u.kernel * u.kernel), ky = row / u.kernel % u.kernel, kx = row % u.kernel;
                // the output columns whose input column ox stride + kx - pad_left is inside [0, w)
                const int before = u.left - kx;  // input columns of padding before ox = 0 reads the first
                const int first = before <= 0 ? 0 : std::min(out_w, (before + u.stride - 1) / u.stride);
                const int last = w - 1 + u.left - kx;  // over stride: the last such ox, if >= 0
                const int end = last < 0 ? first : std::max(first, std::min(out_w, last / u.stride + 1));
                for (int oy = 0; oy < out_h; ++oy) {
                    const int y = oy * u.stride + ky - u.top;
                    if (y < 0 || y >= h) continue;
                    const float *from = src + (static_cast<long>(c) * h + y) * w + first * u.stride + kx - u.left;
                    float *to = &unfolded_[static_cast<size_t>(row) * out_pixels + static_cast<size_t>(oy) * out_w + first];
                    if (u.stride == 2)
                        every_second(from, to, end - first);
                    else
                        for (int i = 0; i < end - first; ++i) to[i] = from[i * u.stride];
                }
            }
        });
        return unfolded_.data();
    }

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
            const size_t tiles = packed_.size() / (static_cast<size_t>(in_channels_) * rows_);
            for (size_t i = 0; i < tiles * in_channels_; ++i)  // [tile][Cin][rows_]: row i's input channel i % Cin
                for (int r = 0; r < rows_; ++r) gated_[i * rows_ + r] = packed_[i * rows_ + r] * gate[i % in_channels_];
            m->weights = gated_.data();
        }
    }

    // The output rows of tiles [first, last) at the pixels from `pixel` (a tile's, or what is left).
    void multiply_tiles(const Image &m, int pixel, int first, int last, std::vector<float> &tail) const
    {
        const int pixels = m.pixels, count = std::min(pixels_, pixels - pixel);
        // a last piece that a narrow tile holds goes through one (7 x 7 = 49 pixels: 3 tiles of 16 and
        // a narrow one of 8 on AVX2, not 4 tiles)
        const bool narrow = count <= kernels_.narrow_pixels;
        const int width = narrow ? kernels_.narrow_pixels : pixels_;
        void (*const tile)(const PointwiseTile &) = narrow ? kernels_.pointwise_tile_narrow : kernels_.pointwise_tile;
        const float *tile_in = m.src + pixel;
        long pitch = pixels;
        if (count < width) {
            tail.assign(static_cast<size_t>(in_channels_) * width, 0.0f);
            for (int c = 0; c < in_channels_; ++c)
                std::memcpy(&tail[static_cast<size_t>(c) * width], m.src + static_cast<size_t>(c) * pixels + pixel,
                            sizeof(float) * count);
            tile_in = tail.data();
            pitch = width;
        }
        float scratch[kLargestTile];  // a tile that ends past the plane or the output channels
        for (int t = first; t < last; ++t) {
            const int rows = std::min(rows_, out_channels_ - t * rows_);
            float *tile_out = m.dst + static_cast<size_t>(t) * rows_ * pixels + pixel;
            const float *weights = m.weights + static_cast<size_t>(t) * in_channels_ * rows_;
            if (count == width && rows == rows_) {
                tile(PointwiseTile{weights, in_channels_, tile_in, pitch, &bias_[t * rows_], tile_out, pixels, swish_});
            } else {
                tile(PointwiseTile{weights, in_channels_, tile_in, pitch, &bias_[t * rows_], scratch, width, swish_});
                for (int r = 0; r < rows; ++r)
                    std::memcpy(tile_out + static_cast<size_t>(r) * pixels, scratch + r * width, sizeof(float) * count);
            }
        }
    }

    const LayerKernels &kernels_;  // the level in use when the layer was made
    const int rows_, pixels_;      // its tile's shape
    struct Unfolding {
        int kernel, stride, top, left, bottom, right;
    };
    Unfolding unfold_{1, 1, 0, 0, 0, 0};  // hkf.PointwiseConv's: none
    int out_channels_ = 0, in_channels_ = 0, image_channels_ = 0;  // in_channels_: image_channels_ k^2
    bool swish_ = false;
    std::vector<float> packed_, bias_;  // weights as [tile][Cin][rows_]; the bias padded to whole tiles
    std::vector<float> gated_;          // the gated weights or input of the image being run
    std::vector<float> unfolded_;       // hkf.UnfoldedConv's input of the image being run
};

// "hkf.SqueezeExcite": a squeeze-and-excitation's gate from its means, g = sigmoid(W2 swish(W1 m + b1) + b2);
// input N x C x 1 x 1 (the means), blobs W1 (R x C x 1 x 1), b1 (R), W2 (C x R x 1 x 1), b2 (C); output
// N x C x 1 x 1. A few thousand products per image: one thread, plain loops (OpenCV ran it as two 1x1
// convolutions and two activations, each with a parallel region of its own).
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

    static cv::Ptr<cv::dnn::Layer> create(cv::dnn::LayerParams &params) { return cv::makePtr<SqueezeExciteLayer>(params); }

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
        std::vector<float> hidden(reduced_);
        for (int image = 0; image < t.in[0].size[0]; ++image) {
            const float *m = t.in[0].ptr<float>() + static_cast<size_t>(image) * channels_;
            float *g = t.out[0].ptr<float>() + static_cast<size_t>(image) * channels_;
            std::copy(b1, b1 + reduced_, hidden.begin());
            for (int c = 0; c < channels_; ++c)
                for (int r = 0; r < reduced_; ++r) hidden[r] += w1_by_channel_[static_cast<size_t>(c) * reduced_ + r] * m[c];
            kernels_.swish(hidden.data(), hidden.data(), reduced_);
            std::copy(b2, b2 + channels_, g);
            for (int r = 0; r < reduced_; ++r)
                for (int c = 0; c < channels_; ++c) g[c] += w2_by_reduced_[static_cast<size_t>(r) * channels_ + c] * hidden[r];
            for (int c = 0; c < channels_; ++c) g[c] = 1.0f / (1.0f + std::exp(-g[c]));
        }
    }

private:
    const LayerKernels &kernels_;  // the level in use when the layer was made
    int reduced_ = 0, channels_ = 0;
    std::vector<float> w1_by_channel_, w2_by_reduced_;  // W1 as C x R, W2 as R x C
};

}  // namespace

float plane_mean(const float *plane, long n) { return layer_kernels_in_use().plane_mean(plane, n); }

void swish_in_place(const float *src, float *dst, long n) { layer_kernels_in_use().swish(src, dst, n); }

void register_fast_layers()
{
    static std::once_flag once;
    std::call_once(once, [] {
        cv::dnn::LayerFactory::registerLayer("hkf.Swish", SwishLayer::create);
        cv::dnn::LayerFactory::registerLayer("hkf.DepthwiseConv", DepthwiseConvLayer::create);
        cv::dnn::LayerFactory::registerLayer("hkf.PointwiseConv", PointwiseConvLayer::create);
        cv::dnn::LayerFactory::registerLayer("hkf.UnfoldedConv", PointwiseConvLayer::create);
        cv::dnn::LayerFactory::registerLayer("hkf.SqueezeExcite", SqueezeExciteLayer::create);
    });
}

}  // namespace hkf_estimator
