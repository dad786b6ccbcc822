// pointwise_conv_layer.cpp - "hkf.PointwiseConv" and "hkf.UnfoldedConv" (see fast_layers.hpp).
#include <algorithm>
#include <cmath>
#include <cstddef>
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

constexpr int kLargestTile = 384;  // floats in the largest level's pointwise tile (8 x 48)

// "hkf.PointwiseConv": a 1x1 convolution (stride 1, no padding) as a matrix product in the level's
// tiles (LayerKernels::pointwise_tile); input N x Cin x H x W, and optionally a second one, a gate N x Cin x 1 x 1 that
// multiplies each input channel first (squeeze-and-excitation's: W (g x) = (W diag g) x, so it scales
// the weights, or the input where that is fewer products, or each pixel tile's input as a task copies it:
// gates_in_tiles); blobs[0] the weights Cout x Cin x 1 x 1, blobs[1] the bias (Cout; none: 0); attribute swish
// (0 or 1); attribute residual (0 or 1): with 1 a last input shaped as the output, added to it as each output tile is
// written (a residual connection's sum, after the swish if any). The weights are packed into tiles once, when the
// layer is made, for the tile of the level in use. A plane's last pixels, fewer than a tile, are copied into a
// zero-padded tile.
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
        residual_ = params.get<int>("residual", 0) != 0;
        if (params.type == "hkf.UnfoldedConv") unfold_ = ConvWindow::read(params);  // else 1 x 1, no padding
        const int k = unfold_.kernel;
        if (blobs.empty() || blobs.size() > 2 || blobs[0].dims != 4 || blobs[0].size[2] != k || blobs[0].size[3] != k ||
            blobs[0].type() != CV_32F || (blobs.size() == 2 && (blobs[1].type() != CV_32F ||
                                                                 static_cast<int>(blobs[1].total()) != blobs[0].size[0])))
            CV_Error(cv::Error::StsBadArg, "hkf.PointwiseConv: wants a Cout x Cin x k x k kernel (k = 1 unless "
                                           "unfolded) and a bias of Cout");
        CV_Assert(rows_ * pixels_ <= kLargestTile && rows_ * kMostPointwiseColumns <= kLargestTile);
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


    bool getMemoryShapes(const std::vector<cv::dnn::MatShape> &inputs, const int,
                         std::vector<cv::dnn::MatShape> &outputs, std::vector<cv::dnn::MatShape> &) const override
    {
        CV_Assert(inputs.size() - (residual_ ? 1 : 0) <= 2 && inputs[0].size() == 4 && inputs[0][1] == image_channels_);
        if (gated(inputs.size()))  // the gate: one value per image and input channel
            CV_Assert(unfold_.kernel == 1 && inputs[1].size() >= 2 && inputs[1][0] == inputs[0][0] &&
                      inputs[1][1] == in_channels_ && cv::dnn::total(inputs[1]) == inputs[0][0] * in_channels_);
        outputs.assign(1, unfold_.output_shape(inputs[0], out_channels_));
        if (residual_) CV_Assert(inputs.back() == outputs[0]);
        return false;
    }

    void forward(cv::InputArrayOfArrays inputs_arr, cv::OutputArrayOfArrays outputs_arr,
                 cv::OutputArrayOfArrays) override
    {
        Tensors t(inputs_arr, outputs_arr);
        const cv::Mat &in = t.in[0];
        cv::Mat &out = t.out[0];
        const int pixels = out.size[2] * out.size[3], batch = in.size[0];
        const Tasks tasks = tasks_of(pixels);
        for (int image = 0; image < batch; ++image) {
            const float *src = in.ptr<float>() + static_cast<size_t>(image) * image_channels_ * in.size[2] * in.size[3];
            const size_t offset = static_cast<size_t>(image) * out_channels_ * pixels;  // the image's output
            Image m{packed_.data(), src, pixels, 0, out.ptr<float>() + offset, pixels, nullptr,
                    residual_ ? t.in.back().ptr<float>() + offset : nullptr, Unfolding{}};
            if (unfold_.kernel > 1) {  // each block unfolds its own pixels (multiply_block)
                m.src = nullptr;
                m.unfold = Unfolding{src, in.size[2], in.size[3], out.size[3]};
            }
            if (gated(t.in.size())) {
                const float *gate = t.in[1].ptr<float>() + static_cast<size_t>(image) * in_channels_;
                if (gates_in_tiles(tasks, pixels))
                    m.gate = gate;
                else
                    apply_gate(gate, &m);
            }
            parallel_tasks(tasks.blocks * tasks.groups, [&](const cv::Range &range) {
                thread_local TaskBuffers buffers;  // the thread's, kept from task to task in its own core's cache
                for (int task = range.start; task < range.end; ++task) {
                    // one pixel tile a task: a group's tasks one after another, its weights kept in the second level
                    const bool by_group = tasks.tiles_per_block == 1;
                    const int block = by_group ? task % tasks.blocks : task / tasks.groups;
                    const int first_row_tile = (by_group ? task / tasks.blocks : task % tasks.groups) * tasks.rows_per_group;
                    const int first_tile = block * tasks.tiles_per_block;
                    multiply_block(m, first_tile, std::min(tasks.pixel_tiles, first_tile + tasks.tiles_per_block),
                                   first_row_tile, std::min(tasks.row_tiles, first_row_tile + tasks.rows_per_group),
                                   buffers);
                }
            });
        }
    }

private:
    // hkf.UnfoldedConv's image (Cin / k^2 planes of h x w) and its output's width; none: image nullptr.
    struct Unfolding {
        const float *image;
        int h, w, out_w;
    };

    // A task's copies of its input: a plane's last pixels (pixel_tile), a gated pixel tile or an unfolded block.
    struct TaskBuffers {
        std::vector<float> tail, copied;
    };

    // One image's product: the packed weights; its input, Cin rows src_pitch floats apart, pixel p at
    // src[p - src_first]; its output planes of `pixels` floats.
    struct Image {
        const float *weights, *src;
        long src_pitch;
        int src_first;
        float *dst;
        int pixels;
        const float *gate;      // Cin values that scale each pixel tile's input rows as they are copied (none: nullptr)
        const float *residual;  // added to dst, laid out as it (none: nullptr)
        Unfolding unfold;       // src unfolded block by block from this (none: image nullptr; src is the input)
    };

    // The unfolded input of the output pixels [first, end) into rows (Cin of them, `pitch` floats apart, pixel p at
    // p - first): row (c, ky, kx) holds, at output pixel (oy, ox), the input at (oy stride + ky - pad_top,
    // ox stride + kx - pad_left), zero outside it, and zero from end - first to pitch.
    void unfold_pixels(const Unfolding &u, int first, int end, float *rows, long pitch) const
    {
        const ConvWindow &k = unfold_;
        for (int row = 0; row < in_channels_; ++row) {
            const int c = row / (k.kernel * k.kernel), ky = row / k.kernel % k.kernel, kx = row % k.kernel;
            int inside, outside;  // the output columns whose input column ox stride + kx - pad_left is inside [0, w)
            columns_inside(kx - k.left, u.w, k.stride, u.out_w, &inside, &outside);
            float *dst = rows + static_cast<long>(row) * pitch;
            std::fill(dst + (end - first), dst + pitch, 0.0f);
            for (int p = first; p < end;) {  // output row by output row
                const int oy = p / u.out_w, from_x = p % u.out_w, to_x = std::min(u.out_w, from_x + (end - p));
                const int y = oy * k.stride + ky - k.top;
                float *to = dst + (p - first) - from_x;  // to[ox]: pixel (oy, ox)
                const bool row_inside = y >= 0 && y < u.h;
                const int a = row_inside ? std::min(to_x, std::max(from_x, inside)) : to_x;
                const int b = row_inside ? std::max(a, std::min(to_x, outside)) : to_x;
                std::fill(to + from_x, to + a, 0.0f);
                if (b > a) {  // input column ox stride + kx - pad_left of row y
                    const float *from = u.image + (static_cast<long>(c) * u.h + y) * u.w + a * k.stride + kx - k.left;
                    if (k.stride == 2)
                        every_second(from, to + a, b - a);
                    else
                        for (int i = 0; i < b - a; ++i) to[a + i] = from[i * k.stride];
                }
                std::fill(to + b, to + to_x, 0.0f);
                p += to_x - from_x;
            }
        }
    }

    // The gate g (Cin values) applied: to a copy of the weights (Cout x Cin products) or of the input
    // (Cin x pixels), whichever is fewer, shared among the threads (up to 1.6 MB of weights read and written);
    // m's weights or src then point at the copy.
    void apply_gate(const float *gate, Image *m)
    {
        const size_t pixels = static_cast<size_t>(m->pixels), cin = static_cast<size_t>(in_channels_);
        if (static_cast<long>(pixels) <= out_channels_) {
            gated_.resize(cin * pixels);
            parallel_tasks(in_channels_, [&](const cv::Range &range) {
                for (size_t c = range.start; c < static_cast<size_t>(range.end); ++c)
                    for (size_t i = 0; i < pixels; ++i) gated_[c * pixels + i] = m->src[c * pixels + i] * gate[c];
            });
            m->src = gated_.data();
        } else {
            gated_.resize(packed_.size());
            const size_t tile = cin * rows_;  // a row tile's packed weights: [Cin][rows_]
            parallel_tasks(static_cast<int>(packed_.size() / tile), [&](const cv::Range &range) {
                for (size_t t = range.start; t < static_cast<size_t>(range.end); ++t)
                    for (size_t c = 0, i = t * tile; c < cin; ++c, i += rows_)
                        for (int r = 0; r < rows_; ++r) gated_[i + r] = packed_[i + r] * gate[c];
            });
            m->weights = gated_.data();
        }
    }

    // The product's tasks. Where a pixel tile's input is small (few input channels: the 112 x 112 layers),
    // blocks of pixel tiles whose input stays in the core's second-level cache, each output row tile of a group
    // running over the whole block: a row tile writes its few output rows as long runs (pixel tile by pixel
    // tile, every output row of the group was written 16 floats at a time). Where it is large (14 x 14 and 7 x 7
    // planes, hundreds of input channels), one pixel tile per task, its input reused from the first-level cache by
    // every row tile (blocks there measured 5-9 % slower), and the output rows in groups of at most 256 kB of
    // weights, a group's pixel tiles one after another, so that its weights are read from the second level after
    // the first tile (7 x 7 layers, whose weights are up to 1.6 MB, 0.8x on two threads). At least 8 tasks to share:
    // blocks no larger than an eighth of the plane, and groups only where there are fewer blocks than that (so that
    // a core reads only its own blocks' input: groups over 3-5 blocks of 320 kB had both cores read all of it). At
    // least 4 or 16 tasks: every layer 1.01x on two threads (16: more groups for the 14 x 14 layers), 32: 1.08x.
    struct Tasks {
        int pixel_tiles, row_tiles, tiles_per_block, blocks, groups, rows_per_group;
    };

    Tasks tasks_of(int pixels) const
    {
        constexpr long kBlockBytes = 320 * 1024;  // of Zen 4's 1 MB and Zen 3's 512 kB second level
        constexpr long kSmallTileBytes = 8 * 1024;  // a pixel tile's input of up to 128 channels at AVX2
        constexpr long kGroupWeightBytes = 256 * 1024;
        constexpr int kLeastTasks = 8;
        Tasks k;
        k.pixel_tiles = (pixels + pixels_ - 1) / pixels_;
        k.row_tiles = (out_channels_ + rows_ - 1) / rows_;
        const long tile_bytes = static_cast<long>(in_channels_) * pixels_ * sizeof(float);
        const long shared_tiles = (k.pixel_tiles + kLeastTasks - 1) / kLeastTasks;  // blocks enough for the tasks
        k.tiles_per_block = tile_bytes > kSmallTileBytes
                                ? 1
                                : static_cast<int>(std::max(1L, std::min({static_cast<long>(k.pixel_tiles),
                                                                          kBlockBytes / tile_bytes, shared_tiles})));
        k.blocks = (k.pixel_tiles + k.tiles_per_block - 1) / k.tiles_per_block;
        k.groups = std::min(k.row_tiles, std::max(1, (kLeastTasks + k.blocks - 1) / k.blocks));
        if (k.tiles_per_block == 1) {  // a group's weights small enough to stay in the second level over its pixel tiles
            const long weight_bytes = static_cast<long>(out_channels_) * in_channels_ * sizeof(float);
            k.groups = std::min<long>(k.row_tiles, std::max<long>(k.groups, (weight_bytes + kGroupWeightBytes - 1) / kGroupWeightBytes));
        }
        k.rows_per_group = (k.row_tiles + k.groups - 1) / k.groups;
        return k;
    }

    // Whether a layer given this many inputs has a gate (its second; a residual is the last).
    bool gated(size_t inputs) const { return inputs == (residual_ ? 3u : 2u); }

    // Whether the gate goes into each task's pixel tile (Image::gate) rather than into a copy of the weights:
    // with one pixel tile a task (many input channels), where the weights' copy is the fewer products but its tiles'
    // copies (one per pixel tile and group) are at most kTileCopies times as many. The weights' copy is shared by
    // the threads and read from the last level (up to 300 kB written for each 14 x 14 projection of WHENet); a task's
    // tile is copied into its own core's cache (Intel Xeon, AVX-512: those layers 0.85-0.90x on two threads, 0.90-0.99x
    // on one; 28 x 28 ones, at 20 times, 1.07x).
    bool gates_in_tiles(const Tasks &tasks, int pixels) const
    {
        constexpr long kTileCopies = 8;
        return tasks.tiles_per_block == 1 && pixels > out_channels_ &&
               static_cast<long>(tasks.groups) * pixels <= kTileCopies * out_channels_;
    }

    // Where one pixel tile's input is, and how it is multiplied: in place; or, a plane's last pixels (fewer than a
    // tile), one or two of them as columns (LayerKernels::pointwise_columns, their input copied into `tail`), alone
    // or after a narrow tile in place that a vector of them fills; or, any other last piece, copied once into
    // `tail`, zero-padded, through a narrow tile where it holds them. 7 x 7 = 49 pixels: at AVX2 3 tiles of 16 and
    // a column (a narrow tile for that one pixel took a quarter of the layer), at AVX-512 a tile of 48 and a
    // column. With m.gate, the tile's input is first copied, gated, into `gated` (then a tile in
    // place there).
    struct PixelTile {
        const float *in;
        long pitch;
        int count, width;  // the pixels taken as vectors (none: 0), and the tile's width
        void (*multiply)(const PointwiseTile &);
        int columns;  // the pixels after them, as columns
    };

    PixelTile pixel_tile(const Image &m, int pixel, std::vector<float> &tail, std::vector<float> &gated) const
    {
        const int count = std::min(pixels_, m.pixels - pixel);
        const float *in = m.src + (pixel - m.src_first);
        if (m.gate == nullptr) return tile_at(in, m.src_pitch, count, tail);
        gated.resize(static_cast<size_t>(in_channels_) * pixels_);
        kernels_.scale_rows(ScaledRows{in, m.src_pitch, m.gate, gated.data(), pixels_, in_channels_, count});
        return tile_at(gated.data(), pixels_, count, tail);
    }

    // The tile of `count` pixels whose input rows start at `in`, `pitch` floats apart (pixel_tile).
    PixelTile tile_at(const float *in, long pitch, int count, std::vector<float> &tail) const
    {
        const int lanes = kernels_.narrow_pixels;
        if (count == pixels_) return PixelTile{in, pitch, count, count, kernels_.pointwise_tile, 0};
        const int vector_pixels = count <= kMostPointwiseColumns ? 0 : lanes;
        if (count >= vector_pixels && count - vector_pixels <= kMostPointwiseColumns) {
            const PixelTile p{in, pitch, vector_pixels, vector_pixels, kernels_.pointwise_tile_narrow,
                              count - vector_pixels};
            tail.resize(static_cast<size_t>(p.columns) * in_channels_ * rows_);
            float *column = tail.data();
            for (int k = 0; k < p.columns; ++k)
                for (int c = 0; c < in_channels_; ++c, column += rows_)
                    std::fill(column, column + rows_, in[static_cast<size_t>(c) * pitch + vector_pixels + k]);
            return p;
        }
        const bool narrow = count <= lanes;
        const int width = narrow ? lanes : pixels_;
        tail.assign(static_cast<size_t>(in_channels_) * width, 0.0f);
        for (int c = 0; c < in_channels_; ++c)
            std::memcpy(&tail[static_cast<size_t>(c) * width], in + static_cast<size_t>(c) * pitch, sizeof(float) * count);
        return PixelTile{tail.data(), width, count, width, narrow ? kernels_.pointwise_tile_narrow : kernels_.pointwise_tile, 0};
    }

    // The output row tiles [first_row, last_row), each over the pixel tiles [first_tile, end_tile) (one, with m.gate);
    // b.copied holds the block's unfolded input (m.unfold) or the tile's gated one.
    void multiply_block(Image m, int first_tile, int end_tile, int first_row, int last_row, TaskBuffers &b) const
    {
        std::vector<float> &tail = b.tail, &copied = b.copied;
        CV_DbgAssert(m.gate == nullptr || end_tile - first_tile == 1);
        if (m.unfold.image != nullptr) {  // the block's pixels unfolded in this core's cache, whole tiles wide
            const long width = static_cast<long>(end_tile - first_tile) * pixels_;
            copied.resize(static_cast<size_t>(in_channels_) * width);
            m.src_first = first_tile * pixels_;
            unfold_pixels(m.unfold, m.src_first, std::min(m.pixels, end_tile * pixels_), copied.data(), width);
            m.src = copied.data();
            m.src_pitch = width;
        }
        PixelTile last = pixel_tile(m, (end_tile - 1) * pixels_, tail, copied);  // the block's last: maybe the tail
        float scratch[kLargestTile];  // a tile that ends past the plane or the output channels
        for (int t = first_row; t < last_row; ++t) {
            const int rows = std::min(rows_, out_channels_ - t * rows_);
            const float *weights = m.weights + static_cast<size_t>(t) * in_channels_ * rows_;
            for (int tile = first_tile; tile < end_tile; ++tile) {
                const int pixel = tile * pixels_;
                const PixelTile p = tile + 1 == end_tile ? last
                                                         : PixelTile{m.src + (pixel - m.src_first), m.src_pitch, pixels_, pixels_,
                                                                     kernels_.pointwise_tile, 0};
                float *tile_out = m.dst + static_cast<size_t>(t) * rows_ * m.pixels + pixel;
                if (p.count > 0 && p.count == p.width && rows == rows_) {
                    p.multiply(PointwiseTile{weights, in_channels_, p.in, p.pitch, &bias_[t * rows_], tile_out, m.pixels, swish_});
                } else if (p.count > 0) {
                    p.multiply(PointwiseTile{weights, in_channels_, p.in, p.pitch, &bias_[t * rows_], scratch, p.width, swish_});
                    for (int r = 0; r < rows; ++r)
                        std::memcpy(tile_out + static_cast<size_t>(r) * m.pixels, scratch + r * p.width, sizeof(float) * p.count);
                }
                if (p.columns > 0) {
                    kernels_.pointwise_columns(PointwiseColumns{weights, in_channels_, tail.data(), p.columns, &bias_[t * rows_], scratch, swish_});
                    for (int k = 0; k < p.columns; ++k)
                        for (int r = 0; r < rows; ++r) tile_out[static_cast<size_t>(r) * m.pixels + p.count + k] = scratch[k * rows_ + r];
                }
                if (m.residual != nullptr) add_residual(m, tile_out - m.dst, rows, p.count + p.columns);
            }
        }
    }

    // m.residual added to the output tile just written: `rows` rows of `count` pixels from dst + at (in the first level).
    static void add_residual(const Image &m, std::ptrdiff_t at, int rows, int count)
    {
        for (int r = 0; r < rows; ++r) {
            float *__restrict out = m.dst + at + static_cast<std::ptrdiff_t>(r) * m.pixels;
            const float *__restrict add = m.residual + at + static_cast<std::ptrdiff_t>(r) * m.pixels;
            for (int i = 0; i < count; ++i) out[i] += add[i];
        }
    }

    const LayerKernels &kernels_;  // the level in use when the layer was made
    const int rows_, pixels_;      // its tile's shape
    ConvWindow unfold_;  // hkf.PointwiseConv's: 1 x 1, no padding
    int out_channels_ = 0, in_channels_ = 0, image_channels_ = 0;  // in_channels_: image_channels_ k^2
    bool swish_ = false, residual_ = false;
    std::vector<float> packed_, bias_;  // weights as [tile][Cin][rows_]; the bias padded to whole tiles
    std::vector<float> gated_;          // the gated weights or input of the image being run
};

}  // namespace

cv::Ptr<cv::dnn::Layer> make_pointwise_conv_layer(cv::dnn::LayerParams &params) { return cv::makePtr<PointwiseConvLayer>(params); }

}  // namespace hkf_estimator
