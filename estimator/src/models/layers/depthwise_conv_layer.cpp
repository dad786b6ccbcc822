// depthwise_conv_layer.cpp - "hkf.DepthwiseConv" (see fast_layers.hpp).
#include <algorithm>
#include <cmath>
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

// "hkf.DepthwiseConv": input N x C x H x W, blobs[0] the kernels C x 1 x k x k, blobs[1] the bias
// (C); attributes kernel, stride, pad_top, pad_left, pad_bottom, pad_right, swish (0 or 1), means (0 or
// 1): with means 1 a second output, each output plane's mean, N x C x 1 x 1 (the global average pooling
// of the squeeze-and-excitation that reads it, taken while the plane is in cache).
class DepthwiseConvLayer : public cv::dnn::Layer {
public:
    explicit DepthwiseConvLayer(const cv::dnn::LayerParams &params)
        : kernels_(layer_kernels_in_use()),
          large_plane_kernels_(kernels_.level == SimdLevel::avx512 ? layer_kernels_of(SimdLevel::avx2) : kernels_)
    {
        setParamsFrom(params);
        window_ = ConvWindow::read(params);
        swish_ = params.get<int>("swish", 0) != 0;
        means_ = params.get<int>("means", 0) != 0;
        if (blobs.size() != 2 || blobs[0].dims != 4 || blobs[0].size[1] != 1 || blobs[0].size[2] != window_.kernel ||
            blobs[0].size[3] != window_.kernel || static_cast<int>(blobs[1].total()) != blobs[0].size[0] ||
            blobs[0].type() != CV_32F || blobs[1].type() != CV_32F)
            CV_Error(cv::Error::StsBadArg, "hkf.DepthwiseConv: wants a C x 1 x k x k kernel and a bias of C");
        blobs[0] = blobs[0].clone();  // continuous, owned
        blobs[1] = blobs[1].clone();
        CV_Assert(kernels_.narrow_pixels <= kMaxLanes && large_plane_kernels_.narrow_pixels <= kMaxLanes);
        interleaved_ = interleave_weights(kernels_.narrow_pixels);
        if (&large_plane_kernels_ != &kernels_)
            large_plane_interleaved_ = interleave_weights(large_plane_kernels_.narrow_pixels);
    }


    bool getMemoryShapes(const std::vector<cv::dnn::MatShape> &inputs, const int,
                         std::vector<cv::dnn::MatShape> &outputs, std::vector<cv::dnn::MatShape> &) const override
    {
        CV_Assert(inputs.size() == 1 && inputs[0].size() == 4 && inputs[0][1] == blobs[0].size[0]);
        outputs.assign(1, window_.output_shape(inputs[0], inputs[0][1]));
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
        if (static_cast<long>(out.size[2]) * out.size[3] <= kInterleavedPixels) {
            const bool large =
                &large_plane_kernels_ != &kernels_ && static_cast<long>(in.size[2]) * in.size[3] >= kLargePlanePixels;
            return forward_interleaved(large ? large_plane_kernels_ : kernels_,
                                       large ? large_plane_interleaved_ : interleaved_, in, out, means);
        }
        const Phases shape = phases_of(in.size[3], out.size[2]);
        parallel_tasks(planes, [&](const cv::Range &range) {
            // zeroed once: each plane then writes the input's places only, the padding's stay zero
            std::vector<float> phases(static_cast<size_t>(window_.stride) * window_.stride * shape.size, 0.0f), extended(shape.count);
            const long plane = static_cast<long>(out.size[2]) * out.size[3];
            for (int p = range.start; p < range.end; ++p) {
                convolve_plane(in, out, p, shape, phases.data(), extended.data());
                if (means != nullptr) means[p] = kernels_.plane_mean(out.ptr<float>() + plane * p, plane);
            }
        });
    }

private:
    // Planes of up to this many output pixels (56 x 56) go through depthwise_interleaved, a vector's channels at
    // once: plane by plane, the split, the copies and the short loops of the smaller planes cost more than their
    // taps (WHENet's layers against the plane path, per-layer minima at AVX2 on one and two threads: 7 x 7 planes
    // 0.43-0.51x, 14 x 14 0.7x, 28 x 28 0.7x, 56 x 56 0.77x; 112 x 112 1.0x and 1.2x, so those stay plane by plane).
    static constexpr long kInterleavedPixels = 56 * 56;
    static constexpr int kMaxLanes = 16;  // AVX-512's
    // At AVX-512, inputs of this many pixels (56 x 56) or more are interleaved a block of 8 channels at a time
    // (AVX2's loops, large_plane_kernels_): 16 planes of that size read and written at once ran slower than 8 on an
    // Intel Xeon (AMX, 2 cores), and 144 channels made 9 blocks for two threads. WHENet's three such layers, per-layer
    // minima, 0.82-0.84x on two threads and 0.81-0.93x on one; its smaller planes stay at 16 (8 there: up to 1.18x).
    static constexpr long kLargePlanePixels = 56 * 56;
    // A task's band of output rows: as many as keep its padded input rows within this (an Intel Xeon's first level is
    // 48 kB). WHENet's 56 x 56 and 28 x 28 layers then run in 3-19 bands, its smaller planes whole; against whole
    // planes, those layers 0.77-0.92x on two threads (more tasks to share, the buffer in the first level), every layer
    // 0.96x; bands of 12 and 32 kB alike, of 48 kB less, of 96 kB no gain, of 6 and 3 kB slower (those layers
    // 1.03-1.24x).
    static constexpr long kBandBytes = 24 * 1024;

    // The kernels and bias as depthwise_interleaved reads them: per block of `lanes` channels, each tap's
    // weights of the block's channels, then the block's bias (zero for channels past the last).
    std::vector<float> interleave_weights(int lanes) const
    {
        const int channels = blobs[0].size[0], taps = window_.kernel * window_.kernel;
        const int blocks = (channels + lanes - 1) / lanes;
        std::vector<float> weights(static_cast<size_t>(blocks) * (taps + 1) * lanes, 0.0f);
        for (int c = 0; c < channels; ++c) {
            float *block = &weights[static_cast<size_t>(c / lanes) * (taps + 1) * lanes];
            for (int t = 0; t < taps; ++t) block[t * lanes + c % lanes] = blobs[0].ptr<float>()[static_cast<size_t>(c) * taps + t];
            block[taps * lanes + c % lanes] = blobs[1].ptr<float>()[c];
        }
        return weights;
    }

    // Every image's planes, a block of `lanes` channels (k's vector) and a band of output rows a task: the band's input
    // rows interleaved into a zero-padded buffer (its left and right padding zeroed once per thread, rows above and
    // below the input zeroed by the bands that take them), convolved, and written back plane by plane; each band's
    // sums added up into the planes' means at the end. `weights` interleaved for k.
    void forward_interleaved(const LayerKernels &k, const std::vector<float> &weights, const cv::Mat &in, cv::Mat &out,
                             float *means) const
    {
        const int lanes = k.narrow_pixels, channels = in.size[1], blocks = (channels + lanes - 1) / lanes;
        const int h = in.size[2], w = in.size[3], out_h = out.size[2], out_w = out.size[3], taps = window_.kernel * window_.kernel;
        const int pitch = std::max(w + window_.left + window_.right, (out_w - 1) * window_.stride + window_.kernel);
        // the padded input of an output row, and as many rows a band as keep it within kBandBytes
        const long band_row_bytes = static_cast<long>(pitch) * lanes * sizeof(float) * window_.stride;
        const int band = static_cast<int>(std::clamp<long>(kBandBytes / band_row_bytes, 1, out_h));
        const int bands = (out_h + band - 1) / band;
        const long out_pixels = static_cast<long>(out_h) * out_w;
        std::vector<float> sums(static_cast<size_t>(in.size[0]) * blocks * bands * lanes);  // a task's lanes each
        parallel_tasks(in.size[0] * blocks * bands, [&](const cv::Range &range) {
            const size_t padded_rows = static_cast<size_t>((band - 1) * window_.stride + window_.kernel);
            std::vector<float> padded(padded_rows * pitch * lanes, 0.0f), result(static_cast<size_t>(band) * out_w * lanes),
                unused(out_pixels);
            const float *from[kMaxLanes];
            float *to[kMaxLanes];
            for (int task = range.start; task < range.end; ++task) {
                const int first = task / bands % blocks * lanes, count = std::min(lanes, channels - first);
                const long plane = static_cast<long>(task / bands / blocks) * channels + first;  // its first plane
                const int first_row = task % bands * band, rows = std::min(band, out_h - first_row);
                for (int c = 0; c < lanes; ++c) {  // a block's missing channels: read any plane, written nowhere
                    from[c] = in.ptr<float>() + (plane + std::min(c, count - 1)) * h * w;
                    float *band_out = out.ptr<float>() + (plane + c) * out_pixels + static_cast<long>(first_row) * out_w;
                    to[c] = c < count ? band_out : unused.data();
                }
                const int first_padded = first_row * window_.stride;
                interleave_band(k, from, BandRows{h, w, pitch, first_padded, (rows - 1) * window_.stride + window_.kernel},
                                padded.data());
                const float *block = &weights[static_cast<size_t>(task / bands % blocks) * (taps + 1) * lanes];
                k.depthwise_interleaved(InterleavedPlanes{padded.data(), pitch, block, block + taps * lanes, window_.kernel,
                                                          window_.stride, rows, out_w, swish_, result.data(),
                                                          &sums[static_cast<size_t>(task) * lanes]});
                k.deinterleave(result.data(), to, static_cast<long>(rows) * out_w);
            }
        });
        for (long p = 0; means != nullptr && p < static_cast<long>(in.size[0]) * channels; ++p) {
            const long image = p / channels, c = p % channels, task = (image * blocks + c / lanes) * bands;
            double sum = 0.0;
            for (int part = 0; part < bands; ++part) sum += sums[static_cast<size_t>(task + part) * lanes + c % lanes];
            means[p] = static_cast<float>(sum / static_cast<double>(out_pixels));
        }
    }

    // Planes of h x w, padded rows of `pitch` pixels; the padded rows [first, first + rows) (padded row r is input
    // row r - pad_top).
    struct BandRows {
        int h, w, pitch, first, rows;
    };

    // A band's rows of a block's planes interleaved into `padded`: the rows outside the input zeroed; row by row where
    // a row holds whole lanes x lanes blocks, small planes whole (a 7-pixel row would be all remainder).
    void interleave_band(const LayerKernels &k, const float *const *from, const BandRows &b, float *padded) const
    {
        const int lanes = k.narrow_pixels, w = b.w;
        const int y0 = std::max(0, b.first - window_.top), y1 = std::max(y0, std::min(b.h, b.first + b.rows - window_.top));
        const size_t row_floats = static_cast<size_t>(b.pitch) * lanes;
        const size_t above = y0 + window_.top - b.first, below = y1 + window_.top - b.first;  // the input's band rows
        std::fill(padded, padded + above * row_floats, 0.0f);
        std::fill(padded + below * row_floats, padded + static_cast<size_t>(b.rows) * row_floats, 0.0f);
        if (y1 == y0) return;
        float *interior = padded + above * row_floats + static_cast<size_t>(window_.left) * lanes;
        const float *row[kMaxLanes];
        if (w < 2 * lanes) {
            for (int c = 0; c < lanes; ++c) row[c] = from[c] + static_cast<long>(y0) * w;
            return k.interleave(row, interior, static_cast<long>(y1 - y0) * w, w, b.pitch);
        }
        for (int y = y0; y < y1; ++y) {
            for (int c = 0; c < lanes; ++c) row[c] = from[c] + static_cast<long>(y) * w;
            k.interleave(row, interior + static_cast<size_t>(y - y0) * row_floats, w, w, w);
        }
    }

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
        const int pitch = (in_w + window_.left + window_.right + window_.stride - 1) / window_.stride;
        const int rows = out_h + (window_.kernel - 1) / window_.stride + 1;
        return Phases{pitch, rows, static_cast<long>(pitch) * rows, static_cast<size_t>(out_h) * pitch};
    }

    // The input plane's floats written to their places in the phases (whose padding is zero already).
    void split_into_phases(const float *src, int h, int w, const Phases &shape, float *phases) const
    {
        for (int px = 0; px < window_.stride; ++px) {
            int first, end;  // the columns c whose input column c stride + px - pad_left is inside [0, w)
            columns_inside(px - window_.left, w, window_.stride, shape.pitch, &first, &end);
            for (int py = 0; py < window_.stride; ++py) {
                float *dst = phases + (py * window_.stride + px) * shape.size + first;
                for (int r = 0; r < shape.rows; ++r, dst += shape.pitch) {
                    const int y = r * window_.stride + py - window_.top;  // the input's row
                    if (y < 0 || y >= h) continue;
                    const float *row = src + static_cast<long>(y) * w + first * window_.stride + px - window_.left;
                    if (window_.stride == 1)
                        std::memcpy(dst, row, sizeof(float) * (end - first));
                    else if (window_.stride == 2)
                        every_second(row, dst, end - first);
                    else
                        for (int c = 0; c < end - first; ++c) dst[c] = row[c * window_.stride];
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
            for (int ky = 0; ky < window_.kernel; ++ky)
                for (int kx = 0; kx < window_.kernel; ++kx)
                    acc += weights[ky * window_.kernel + kx] * in.phases[((ky % window_.stride) * window_.stride + kx % window_.stride) * in.size +
                                                                  (ky / window_.stride) * in.pitch + kx / window_.stride + j];
            sum[j] = acc;
        }
    }

    // One channel's plane: split into phases (above), then the bias and all kernel taps summed for each
    // "extended" output j = oy pitch + ox, ox < pitch, which reads the phase of (ky, kx) at
    // j + (ky / stride) pitch + kx / stride, in one long loop over j: the compiler vectorises it whatever
    // the plane's width (on 7 x 7 planes a loop per output row would be as short as the vector), with
    // contiguous loads at any stride. The columns ox >= the output's width are then dropped, and the swish taken
    // as the rows are copied out.
    void convolve_plane(const cv::Mat &in, cv::Mat &out, int plane, const Phases &shape, float *phases,
                        float *extended) const
    {
        const int channel = plane % in.size[1];
        const int h = in.size[2], w = in.size[3], out_h = out.size[2], out_w = out.size[3];
        split_into_phases(in.ptr<float>() + static_cast<size_t>(plane) * h * w, h, w, shape, phases);
        const float *weights = blobs[0].ptr<float>() + static_cast<size_t>(channel) * window_.kernel * window_.kernel;
        const float bias = blobs[1].ptr<float>()[channel];
        DepthwiseTaps *taps = window_.kernel == 3 && window_.stride == 1   ? kernels_.taps_3x3_stride1
                              : window_.kernel == 3 && window_.stride == 2 ? kernels_.taps_3x3_stride2
                              : window_.kernel == 5 && window_.stride == 1 ? kernels_.taps_5x5_stride1
                              : window_.kernel == 5 && window_.stride == 2 ? kernels_.taps_5x5_stride2
                                                             : nullptr;
        const PhasePlanes planes{phases, shape.size, shape.pitch};
        if (taps != nullptr)
            taps(planes, weights, bias, extended, shape.count);
        else
            any_taps(planes, weights, bias, extended, shape.count);
        float *dst = out.ptr<float>() + static_cast<size_t>(plane) * out_h * out_w;
        for (int oy = 0; oy < out_h; ++oy) {  // the swish on the way out: no second pass over the plane
            const float *row = extended + static_cast<size_t>(oy) * shape.pitch;
            if (swish_)
                kernels_.swish(row, dst + static_cast<size_t>(oy) * out_w, out_w);
            else
                std::memcpy(dst + static_cast<size_t>(oy) * out_w, row, sizeof(float) * out_w);
        }
    }

    const LayerKernels &kernels_;              // the level in use when the layer was made
    const LayerKernels &large_plane_kernels_;  // its table for inputs of kLargePlanePixels or more (AVX-512: AVX2's)
    ConvWindow window_;
    bool swish_ = false, means_ = false;
    std::vector<float> interleaved_;              // interleave_weights() for kernels_
    std::vector<float> large_plane_interleaved_;  // for large_plane_kernels_, where it is another table (else empty)
};

}  // namespace

cv::Ptr<cv::dnn::Layer> make_depthwise_conv_layer(cv::dnn::LayerParams &params) { return cv::makePtr<DepthwiseConvLayer>(params); }

}  // namespace hkf_estimator
