// layer_kernels_impl.hpp - the layers' inner loops, included once by each level's file
// (layer_kernels_LEVEL.cpp), which defines first:
//   HKF_KERNELS_NAMESPACE   a namespace of the level's own, so that no function is shared between levels
//                           (a function built with AVX-512 must never be the one a baseline caller links)
//   HKF_KERNELS_TABLE       the table's name (layer_kernels.hpp)
//   HKF_KERNELS_LEVEL, HKF_KERNELS_NAME
//   HKF_LANES               floats in one of the level's vector registers (16, 8 or 4)
//   HKF_TILE_ROWS, HKF_TILE_VECTORS
//                           the pointwise tile: rows x vectors of running sums, chosen to fill the level's
//                           register file without spilling: AVX-512 8 x 3 (24 of 32 zmm: 49 pixels a tile of
//                           48 and a column; against 8 x 2, on an Intel Xeon, the 7 x 7 layers 0.78-0.94x on one
//                           thread and 0.87-0.96x on two, every layer 0.94x and 0.98x; 12 x 2 gained on one thread
//                           only), AVX2 6 x 2 (12 of
//                           16 ymm, beside 2 inputs and a broadcast weight), SSE2 4 x 3 (12 of 16 xmm), NEON
//                           8 x 2 (16 of 32 registers)
// Only this file's own functions and compiler built-ins are used here: no inline function of a shared
// header, which the linker might take from another level's file.
#include <cstdint>
#include <cstring>
#include <utility>

#include "layer_kernels.hpp"

namespace hkf_estimator {
namespace HKF_KERNELS_NAMESPACE {
namespace {

typedef float Vector __attribute__((vector_size(HKF_LANES * sizeof(float))));
constexpr int kRows = HKF_TILE_ROWS, kVectors = HKF_TILE_VECTORS, kPixels = HKF_TILE_VECTORS * HKF_LANES;

typedef std::uint32_t Bits __attribute__((vector_size(HKF_LANES * sizeof(float))));

// A float's bits, or a vector's lane by lane: for exp_approx, which is written once for both.
template <typename T> struct BitsOf { typedef std::uint32_t type; };
template <> struct BitsOf<Vector> { typedef Bits type; };

template <typename T>
inline T absolute(T v)
{
    typename BitsOf<T>::type bits;
    __builtin_memcpy(&bits, &v, sizeof bits);
    bits &= 0x7FFFFFFFu;
    __builtin_memcpy(&v, &bits, sizeof v);
    return v;
}

// t clamped to [-87, 88]. A float's as t + relu(-87 - t) and t - relu(t - 88), relu(d) = (d + |d|) / 2,
// which leave a t inside exactly as it is (a comparison would be a branch GCC does not if-convert in a
// loop over floats). A vector's by the x86 levels' min and max instructions (GCC makes a compare and a
// blend of a comparison, two operations for one; the swish went from 1.16 to 0.95 ns a float at SSE2, from
// 0.34 to 0.29 at AVX2 and from 0.26 to 0.25 at AVX-512), elsewhere (NEON) by comparisons.
inline float clamp_exponent(float t)
{
    const float below = -87.0f - t;
    t += 0.5f * (below + absolute(below));
    const float above = t - 88.0f;
    return t - 0.5f * (above + absolute(above));
}

inline Vector clamp_exponent(Vector t)
{
    const Vector low = Vector{} - 87.0f, high = Vector{} + 88.0f;
#if HKF_LANES == 4 && defined(__SSE__)
    return __builtin_ia32_minps(__builtin_ia32_maxps(t, low), high);
#elif HKF_LANES == 16 && defined(__clang__)
    return __builtin_ia32_minps512(__builtin_ia32_maxps512(t, low, 4), high, 4);  // 4: the current rounding
#elif HKF_LANES == 16
    return __builtin_ia32_minps512_mask(__builtin_ia32_maxps512_mask(t, low, t, 0xFFFF, 4), high, t, 0xFFFF, 4);
#elif HKF_LANES == 8
    return __builtin_ia32_minps256(__builtin_ia32_maxps256(t, low), high);
#else
    t = t < low ? low : t;
    return t > high ? high : t;
#endif
}

// exp(t) for t in [-87, 88] (clamped outside), of a float or lane by lane: t = k ln2 + r with
// |r| <= ln2 / 2 (Cody-Waite), exp(r) by a degree-5 polynomial of least relative error there
// (dev/fit/exp_polynomial.py: 2.1e-7 in float arithmetic, as the Taylor series to r^6 with one
// multiply-add more), 2^k by the float's exponent bits; k from the round-to-nearest trick (adding
// 1.5 * 2^23 leaves k in the low mantissa bits), so no float-to-int conversion is made. The polynomial in
// Horner's form where multiply and add are one instruction; without (SSE2, AVX) as Estrin's pairs, whose shorter
// chain of dependent steps ran the pass at SSE2 1-3 % faster (alternating runs) and the swish at AVX 0.59 -> 0.55 ns
// a float (at AVX2, with FMA, Estrin's was 6 % slower).
template <typename T>
T exp_approx(T t)
{
    t = clamp_exponent(t);
    const float magic = 12582912.0f;  // 1.5 * 2^23
    const T shifted = t * 1.44269504088896341f + magic;
    const T k = shifted - magic;
    const T r = (t - k * 0.693145751953125f) - k * 1.428606765330187e-06f;
#if defined(__FMA__) || defined(__aarch64__)
    const T p = 1.000000119e+00f +
                r * (9.999997020e-01f +
                     r * (4.999889433e-01f + r * (1.666757464e-01f + r * (4.191538319e-02f + r * 8.297652006e-03f))));
#else
    const T r2 = r * r;
    const T p = (1.000000119e+00f + r * 9.999997020e-01f) +
                r2 * ((4.999889433e-01f + r * 1.666757464e-01f) + r2 * (4.191538319e-02f + r * 8.297652006e-03f));
#endif
    typename BitsOf<T>::type shifted_bits, p_bits;
    __builtin_memcpy(&shifted_bits, &shifted, sizeof shifted_bits);
    __builtin_memcpy(&p_bits, &p, sizeof p_bits);
    p_bits += (shifted_bits - 0x4B400000u) << 23;  // times 2^k: k added to the exponent
    T out;
    __builtin_memcpy(&out, &p_bits, sizeof out);
    return out;
}

// x / (1 + exp(-x)), of a float or of a vector's lanes. (A reciprocal estimate and a Newton step instead
// of the division ran 20 % slower on Zen 4: the divide is not what bounds it.)
template <typename T>
T swish_of(T x)
{
    return x / (1.0f + exp_approx(-x));
}

// How far ahead of the tile's running weights (floats) they are asked for, for the second-level cache: the 7 x 7
// layers' weights (up to 1.6 MB each, 10 MB in all) come from memory once a pass, and the hardware's own
// prefetch left their tiles waiting on it (a 1152 -> 192 layer with its weights out of the caches 0.26 -> 0.23 ms,
// 320 -> 1280 0.52 -> 0.41 ms at AVX2; 1024 and 2048 floats ahead alike, 256 too few).
constexpr long kWeightsAhead = 1024;

// The tile: kRows x VECTORS vector registers of running sums, one broadcast weight per row and input
// channel (a fused multiply-add where the level has one); the swish, if asked, on the sums. VECTORS is
// kVectors, or 1 for a plane's last few pixels (a narrow tile).
template <int VECTORS>
void pointwise_tile(const PointwiseTile &t)
{
    // Every loop over rows and vectors unrolled, so that the sums stay in registers (GCC keeps an array it
    // indexes in a loop in memory).
    Vector sum[kRows][VECTORS];
#pragma GCC unroll 16
    for (int r = 0; r < kRows; ++r)
#pragma GCC unroll 4
        for (int v = 0; v < VECTORS; ++v) sum[r][v] = Vector{} + t.bias[r];
    for (int c = 0; c < t.cin; ++c) {
        Vector x[VECTORS];
#pragma GCC unroll 4
        for (int v = 0; v < VECTORS; ++v) __builtin_memcpy(&x[v], t.in + c * t.in_pitch + v * HKF_LANES, sizeof x[v]);
        const float *w = t.weights + static_cast<long>(c) * kRows;
        __builtin_prefetch(w + kWeightsAhead, 0, 1);
#pragma GCC unroll 16
        for (int r = 0; r < kRows; ++r)
#pragma GCC unroll 4
            for (int v = 0; v < VECTORS; ++v) sum[r][v] += x[v] * w[r];  // w[r] broadcast
    }
    if (t.swish) {  // in registers, before the store: no second pass over the output
#pragma GCC unroll 16
        for (int r = 0; r < kRows; ++r)
#pragma GCC unroll 4
            for (int v = 0; v < VECTORS; ++v) sum[r][v] = swish_of(sum[r][v]);
    }
#pragma GCC unroll 16
    for (int r = 0; r < kRows; ++r)
#pragma GCC unroll 4
        for (int v = 0; v < VECTORS; ++v)
            __builtin_memcpy(t.out + r * t.out_pitch + v * HKF_LANES, &sum[r][v], sizeof sum[r][v]);
}

constexpr int greatest_common_divisor(int a, int b) { return b == 0 ? a : greatest_common_divisor(b, a % b); }

// C columns (PointwiseColumns) over the packed weights at once, each weight vector loaded once for the C: the
// weights and a column are both cin x kRows floats, so an output is their element-wise products summed over
// every kRows-th float. Vector sums over spans of lcm(kRows, lanes) floats (each lane then always the same
// row), enough spans that each column has four or more sums to wait on; the spans' lanes added by row at the end.
template <int C>
void columns_of(const PointwiseColumns &p)
{
    constexpr int span = kRows / greatest_common_divisor(kRows, HKF_LANES) * HKF_LANES;
    constexpr int chunk = span * ((4 * HKF_LANES + span - 1) / span), vectors = chunk / HKF_LANES;
    Vector sum[C][vectors];
#pragma GCC unroll 8
    for (int k = 0; k < C; ++k)
#pragma GCC unroll 8
        for (int v = 0; v < vectors; ++v) sum[k][v] = Vector{};
    const long n = static_cast<long>(p.cin) * kRows;
    long j = 0;
    for (; j + chunk <= n; j += chunk) {
#pragma GCC unroll 8
        for (int v = 0; v < vectors; ++v) {
            Vector w;
            __builtin_memcpy(&w, p.weights + j + v * HKF_LANES, sizeof w);
#pragma GCC unroll 8
            for (int k = 0; k < C; ++k) {
                Vector x;
                __builtin_memcpy(&x, p.columns + k * n + j + v * HKF_LANES, sizeof x);
                sum[k][v] += w * x;
            }
        }
    }
    for (int k = 0; k < C; ++k) {
        float lanes[chunk];
        __builtin_memcpy(lanes, sum[k], sizeof lanes);
        for (long i = j; i < n; ++i) lanes[i - j] += p.weights[i] * p.columns[k * n + i];  // the last floats, fewer than a chunk
        float *out = p.sums + k * kRows;
        for (int r = 0; r < kRows; ++r) out[r] = p.bias[r];
        for (int i = 0; i < chunk; ++i) out[i % kRows] += lanes[i];
        if (p.swish)
            for (int r = 0; r < kRows; ++r) out[r] = swish_of(out[r]);
    }
}

void pointwise_columns(const PointwiseColumns &p)
{
    static_assert(kMostPointwiseColumns == 2, "one columns_of<C> for each count");
    if (p.count == 2) return columns_of<2>(p);
    columns_of<1>(p);
}

// All K^2 taps of one output summed in registers (one store per output), the loop over j vectorised:
// every tap reads its phase at j plus a fixed offset, so the loads are contiguous at any stride.
template <int K, int STRIDE>
void taps(const PhasePlanes &in, const float *weights, float bias, float *__restrict sum, std::size_t count)
{
    float w[K * K];
    __builtin_memcpy(w, weights, sizeof w);
    const long size = in.size, pitch = in.pitch;
    for (std::size_t j = 0; j < count; ++j) {
        const float *at = in.phases + j;
        float acc = bias;
        for (int ky = 0; ky < K; ++ky)
            for (int kx = 0; kx < K; ++kx)
                acc += w[ky * K + kx] * at[((ky % STRIDE) * STRIDE + kx % STRIDE) * size + (ky / STRIDE) * pitch + kx / STRIDE];
        sum[j] = acc;
    }
}

// R outputs of a row, the first's window from `at`: each tap's weights loaded once for the R outputs (k and
// stride constants once inlined into interleaved_taps<K, STRIDE>).
template <int R>
inline void interleaved_outputs(const InterleavedPlanes &p, int k, int stride, const float *at, Vector bias, float *out)
{
    Vector acc[R];
#pragma GCC unroll 8
    for (int r = 0; r < R; ++r) acc[r] = bias;
    for (int ky = 0; ky < k; ++ky)
        for (int kx = 0; kx < k; ++kx) {
            Vector w;
            __builtin_memcpy(&w, p.weights + (ky * k + kx) * HKF_LANES, sizeof w);
            const float *tap = at + (static_cast<long>(ky) * p.pitch + kx) * HKF_LANES;
#pragma GCC unroll 8
            for (int r = 0; r < R; ++r) {
                Vector x;
                __builtin_memcpy(&x, tap + r * stride * HKF_LANES, sizeof x);
                acc[r] += x * w;
            }
        }
#pragma GCC unroll 8
    for (int r = 0; r < R; ++r) __builtin_memcpy(out + r * HKF_LANES, &acc[r], sizeof acc[r]);
}

// One vector of channels, eight output pixels of a row at a time (then four, then one; eight against four, the
// 14 x 14 to 56 x 56 layers about 0.96x at SSE2 and AVX2, level at AVX-512; sixteen, slower at every level, the
// 28 x 28 layers 1.13-1.24x): every tap a load of its weights and one of
// the input per output (no plane split by phases, no copies: the row's few outputs need no long loop over j); then the
// swish and the sums in a pass of their own (inside the loop, each output's exp and division waited on the
// taps before it). K and STRIDE 0: the plane's own, at run time.
template <int K, int STRIDE>
void interleaved_taps(const InterleavedPlanes &p)
{
    const int k = K != 0 ? K : p.kernel, stride = STRIDE != 0 ? STRIDE : p.stride;
    Vector bias;
    __builtin_memcpy(&bias, p.bias, sizeof bias);
    float *out = p.out;
    for (int oy = 0; oy < p.out_h; ++oy) {
        const float *row = p.in + static_cast<long>(oy) * stride * p.pitch * HKF_LANES;
        int ox = 0;
        for (; ox + 8 <= p.out_w; ox += 8, out += 8 * HKF_LANES)
            interleaved_outputs<8>(p, k, stride, row + static_cast<long>(ox) * stride * HKF_LANES, bias, out);
        for (; ox + 4 <= p.out_w; ox += 4, out += 4 * HKF_LANES)
            interleaved_outputs<4>(p, k, stride, row + static_cast<long>(ox) * stride * HKF_LANES, bias, out);
        for (; ox < p.out_w; ++ox, out += HKF_LANES)
            interleaved_outputs<1>(p, k, stride, row + static_cast<long>(ox) * stride * HKF_LANES, bias, out);
    }
    Vector total = Vector{};
    for (float *v = p.out; v < out; v += HKF_LANES) {
        Vector x;
        __builtin_memcpy(&x, v, sizeof x);
        if (p.swish) {
            x = swish_of(x);
            __builtin_memcpy(v, &x, sizeof x);
        }
        total += x;
    }
    __builtin_memcpy(p.sums, &total, sizeof total);
}

// The butterfly's step H on a pair of rows (a, b) of a lanes x lanes block: the H-wide pieces at odd places
// of a and at even places of b swapped, each row one two-input shuffle of constant lanes
// (__builtin_shufflevector: GCC 12 and clang alike); the steps H = lanes / 2, ..., 1 transpose the block.
template <int H, int... I>
inline void swap_pieces(Vector &a, Vector &b, std::integer_sequence<int, I...>)
{
    const Vector x = __builtin_shufflevector(a, b, ((I & H) != 0 ? HKF_LANES + I - H : I)...);
    const Vector y = __builtin_shufflevector(a, b, ((I & H) != 0 ? HKF_LANES + I : I + H)...);
    a = x;
    b = y;
}

template <int H>
inline void butterfly(Vector (&rows)[HKF_LANES])
{
#pragma GCC unroll 16
    for (int r = 0; r < HKF_LANES; ++r)
        if ((r & H) == 0) swap_pieces<H>(rows[r], rows[r + H], std::make_integer_sequence<int, HKF_LANES>());
    if constexpr (H > 1) butterfly<H / 2>(rows);
}

// dst[(i / w pitch + i % w) lanes + c] = planes[c][i], i < n: lanes planes' pixels interleaved, a lanes x lanes
// block at a time, each plane's rows of w pixels pitch pixels apart in dst (a padded plane's interior; pitch = w:
// one after another).
void interleave(const float *const *planes, float *dst, long n, long w, long pitch)
{
    long i = 0, column = 0;  // pixel i's column; `row` its row's first float in dst
    float *row = dst;
    const auto next_pixel = [&] {
        if (++column == w) {
            column = 0;
            row += pitch * HKF_LANES;
        }
    };
    for (; i + HKF_LANES <= n; i += HKF_LANES) {
        Vector rows[HKF_LANES];
#pragma GCC unroll 16
        for (int c = 0; c < HKF_LANES; ++c) __builtin_memcpy(&rows[c], planes[c] + i, sizeof rows[c]);
        butterfly<HKF_LANES / 2>(rows);
#pragma GCC unroll 16
        for (int k = 0; k < HKF_LANES; ++k) {
            __builtin_memcpy(row + column * HKF_LANES, &rows[k], sizeof rows[k]);
            next_pixel();
        }
    }
    for (; i < n; ++i, next_pixel())
        for (int c = 0; c < HKF_LANES; ++c) row[column * HKF_LANES + c] = planes[c][i];
}

// planes[c][i] = src[i lanes + c], i < n: the other way.
void deinterleave(const float *src, float *const *planes, long n)
{
    long i = 0;
    for (; i + HKF_LANES <= n; i += HKF_LANES) {
        Vector rows[HKF_LANES];
#pragma GCC unroll 16
        for (int k = 0; k < HKF_LANES; ++k) __builtin_memcpy(&rows[k], src + (i + k) * HKF_LANES, sizeof rows[k]);
        butterfly<HKF_LANES / 2>(rows);
#pragma GCC unroll 16
        for (int c = 0; c < HKF_LANES; ++c) __builtin_memcpy(planes[c] + i, &rows[c], sizeof rows[c]);
    }
    for (; i < n; ++i)
        for (int c = 0; c < HKF_LANES; ++c) planes[c][i] = src[i * HKF_LANES + c];
}

void depthwise_interleaved(const InterleavedPlanes &p)
{
    if (p.kernel == 3 && p.stride == 1) return interleaved_taps<3, 1>(p);
    if (p.kernel == 3 && p.stride == 2) return interleaved_taps<3, 2>(p);
    if (p.kernel == 5 && p.stride == 1) return interleaved_taps<5, 1>(p);
    if (p.kernel == 5 && p.stride == 2) return interleaved_taps<5, 2>(p);
    interleaved_taps<0, 0>(p);
}

// dst[i] = f(src[i]), i < n: vector by vector, the last floats, fewer than a vector, one by one (f of a Vector
// and of a float: a generic lambda).
template <typename F>
inline void each_float(const float *src, float *dst, long n, F f)
{
    long i = 0;
    for (; i + HKF_LANES <= n; i += HKF_LANES) {
        Vector x;
        __builtin_memcpy(&x, src + i, sizeof x);
        x = f(x);
        __builtin_memcpy(dst + i, &x, sizeof x);
    }
    for (; i < n; ++i) dst[i] = f(src[i]);
}

void swish(const float *src, float *dst, long n)
{
    each_float(src, dst, n, [](auto x) { return swish_of(x); });
}

// 16 running sums (a loop the compiler vectorises; one sum would be a chain of dependent additions),
// added in double at the end.
float plane_mean(const float *plane, long n)
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

// Row by row: vector by vector, the last floats of a row one by one.
void scale_rows(const ScaledRows &p)
{
    const float *src = p.src;
    float *dst = p.dst;
    const long n = p.n;
    for (long r = 0; r < p.rows; ++r, src += p.src_pitch, dst += p.dst_pitch) {
        const float s = p.scales[r];
        long i = 0;
        for (; i + HKF_LANES <= n; i += HKF_LANES) {
            Vector x;
            __builtin_memcpy(&x, src + i, sizeof x);
            x *= s;
            __builtin_memcpy(dst + i, &x, sizeof x);
        }
        for (; i < n; ++i) dst[i] = src[i] * s;
    }
}

// Row by row: vector by vector, the last floats of a row one by one.
void accumulate_rows(const float *a, long pitch, const float *x, long rows, long n, float *y)
{
    for (long i = 0; i < rows; ++i, a += pitch) {
        const float s = x[i];
        long j = 0;
        for (; j + HKF_LANES <= n; j += HKF_LANES) {
            Vector sum, row;
            __builtin_memcpy(&sum, y + j, sizeof sum);
            __builtin_memcpy(&row, a + j, sizeof row);
            sum += row * s;
            __builtin_memcpy(y + j, &sum, sizeof sum);
        }
        for (; j < n; ++j) y[j] += a[j] * s;
    }
}

// 1 / (1 + exp(-x)), of a float or of a vector's lanes.
template <typename T>
T sigmoid_of(T x)
{
    return 1.0f / (1.0f + exp_approx(-x));
}

void sigmoid(const float *src, float *dst, long n)
{
    each_float(src, dst, n, [](auto x) { return sigmoid_of(x); });
}

}  // namespace
}  // namespace HKF_KERNELS_NAMESPACE

extern const LayerKernels HKF_KERNELS_TABLE = {
    HKF_KERNELS_LEVEL,
    HKF_KERNELS_NAME,
    HKF_KERNELS_NAMESPACE::kRows,
    HKF_KERNELS_NAMESPACE::kPixels,
    HKF_LANES,
    HKF_KERNELS_NAMESPACE::pointwise_tile<HKF_KERNELS_NAMESPACE::kVectors>,
    HKF_KERNELS_NAMESPACE::pointwise_tile<1>,
    HKF_KERNELS_NAMESPACE::pointwise_columns,
    HKF_KERNELS_NAMESPACE::taps<3, 1>,
    HKF_KERNELS_NAMESPACE::taps<3, 2>,
    HKF_KERNELS_NAMESPACE::taps<5, 1>,
    HKF_KERNELS_NAMESPACE::taps<5, 2>,
    HKF_KERNELS_NAMESPACE::depthwise_interleaved,
    HKF_KERNELS_NAMESPACE::interleave,
    HKF_KERNELS_NAMESPACE::deinterleave,
    HKF_KERNELS_NAMESPACE::swish,
    HKF_KERNELS_NAMESPACE::plane_mean,
    HKF_KERNELS_NAMESPACE::scale_rows,
    HKF_KERNELS_NAMESPACE::accumulate_rows,
    HKF_KERNELS_NAMESPACE::sigmoid,
};

}  // namespace hkf_estimator
