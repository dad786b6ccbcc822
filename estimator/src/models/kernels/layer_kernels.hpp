// layer_kernels.hpp - the inner loops of the estimator's own layers (models/layers/), one table per
// instruction-set level. Each level's table is the same source (layer_kernels_impl.hpp) built by its own
// file with that level's compiler flags and a tile shaped for its registers; the layers take the table
// that simd_level.hpp chose. Nothing here depends on OpenCV.
#pragma once

#include <cstddef>

namespace hkf_estimator {

enum class SimdLevel { baseline, avx, avx2, avx512 };  // baseline: SSE2 on x86-64, NEON on aarch64

// One tile of a 1x1 convolution: tile_rows output channels x tile_pixels pixels, summed over cin input
// channels, and the swish after it if asked.
struct PointwiseTile {
    const float *weights;  // packed [cin][tile_rows]
    int cin;
    const float *in;       // cin rows of in_pitch floats from the tile's first pixel
    long in_pitch;
    const float *bias;     // tile_rows
    float *out;            // tile_rows rows of out_pitch floats
    long out_pitch;
    bool swish;            // the output x / (1 + exp(-x)) of the sum x
};

// A plane's last one or two pixels past its tiles (7 x 7 = 49 pixels: 3 tiles of 16 and one pixel at AVX2),
// each a dot product of a row tile's packed weights with the pixel's input column repeated tile_rows times, so
// that no lane idles (a narrow tile for one pixel leaves all lanes but one idle, and waits on its few sums).
constexpr int kMostPointwiseColumns = 2;
struct PointwiseColumns {
    const float *weights;  // packed [cin][tile_rows], as PointwiseTile's
    int cin;
    const float *columns;  // count x cin x tile_rows: column k's input channel c at (k cin + c) tile_rows + r, every r
    int count;             // 1 .. kMostPointwiseColumns
    const float *bias;     // tile_rows
    float *sums;           // count x tile_rows: column k's output row r at k tile_rows + r
    bool swish;
};

// A depthwise convolution's input plane, zero-padded and split by row and column modulo the stride
// (layers/depthwise_conv_layer.cpp, convolve_plane; at stride 1 the padded plane itself): stride^2 phases of `size`
// floats one after the other, rows of `pitch` floats.
struct PhasePlanes {
    const float *phases;
    long size;
    int pitch;
};

// Its "extended" outputs sum[j], j < count: bias plus every K x K tap (ky, kx) at phase
// (ky % STRIDE) STRIDE + kx % STRIDE, index j + (ky / STRIDE) pitch + kx / STRIDE.
typedef void DepthwiseTaps(const PhasePlanes &in, const float *weights, float bias, float *sum, std::size_t count);

// A depthwise convolution of one vector's channels at once (the estimator's small planes, where a plane's own
// loop is mostly overhead): the zero-padded input with the channels interleaved, pixel (y, x)'s channel c at
// (y pitch + x) lanes + c; tap (ky, kx)'s weights at (ky kernel + kx) lanes; the output pixels (oy, ox),
// out_h x out_w, interleaved alike, each the bias plus the taps at (oy stride + ky, ox stride + kx), the swish
// on it if asked; each channel's sum over its output pixels into sums.
struct InterleavedPlanes {
    const float *in;
    int pitch;  // pixels in a padded row
    const float *weights, *bias;
    int kernel, stride, out_h, out_w;
    bool swish;
    float *out, *sums;
};

// dst[r dst_pitch + i] = src[r src_pitch + i] scales[r], r < rows, i < n (a gate on a pixel tile's input rows).
struct ScaledRows {
    const float *src;
    long src_pitch;
    const float *scales;
    float *dst;
    long dst_pitch, rows, n;
};

struct LayerKernels {
    SimdLevel level;
    const char *name;            // as HKF_SIMD spells it: avx512, avx2, avx, sse2 or neon
    int tile_rows, tile_pixels;  // the pointwise tile: output channels x pixels
    int narrow_pixels;           // the narrow tile's pixels: one vector
    void (*pointwise_tile)(const PointwiseTile &tile);
    void (*pointwise_tile_narrow)(const PointwiseTile &tile);  // tile_rows x narrow_pixels
    void (*pointwise_columns)(const PointwiseColumns &columns);
    DepthwiseTaps *taps_3x3_stride1, *taps_3x3_stride2, *taps_5x5_stride1, *taps_5x5_stride2;
    void (*depthwise_interleaved)(const InterleavedPlanes &planes);  // narrow_pixels (one vector's) channels
    // dst[(i / w pitch + i % w) lanes + c] = planes[c][i], i < n: rows of w pixels, pitch pixels apart in dst
    void (*interleave)(const float *const *planes, float *dst, long n, long w, long pitch);
    void (*deinterleave)(const float *src, float *const *planes, long n);  // the other way
    void (*swish)(const float *src, float *dst, long n);  // x / (1 + exp(-x)); dst may be src
    float (*plane_mean)(const float *plane, long n);      // n > 0
    void (*scale_rows)(const ScaledRows &rows);
    // y[j] += sum over i < rows of x[i] a[i pitch + j], j < n: row by row, each row of a read once and in order (the
    // squeeze-and-excitation's two products, whose weights come from the last-level cache); y in the first level
    void (*accumulate_rows)(const float *a, long pitch, const float *x, long rows, long n, float *y);
    void (*sigmoid)(const float *src, float *dst, long n);  // 1 / (1 + exp(-x)); dst may be src
};

extern const LayerKernels kBaselineKernels;
#if defined(__x86_64__)
extern const LayerKernels kAvxKernels;     // AVX without FMA (Sandy and Ivy Bridge, Bulldozer)
extern const LayerKernels kAvx2Kernels;    // AVX2 with FMA
extern const LayerKernels kAvx512Kernels;  // AVX-512F
#endif

}  // namespace hkf_estimator
