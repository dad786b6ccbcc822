// test_layer_kernels.cpp - each instruction-set level's loops (estimator/src/models/kernels/) against plain
// loops in double, without OpenCV, so that the same file is built for another architecture (aarch64's
// NEON, run under qemu-user: tests/estimator/kernels_aarch64_test.sh) as well as for this one. The tile on
// every shape a layer gives it (whole and cut at either edge: the layer pads those to a whole tile), the
// depthwise taps of WHENet's kernels and strides, the swish and the sigmoid over +-200 and beyond, a plane's mean,
// scaled rows, rows accumulated.
// usage: test_layer_kernels [LEVEL...]   (default: every level built in; a level this CPU lacks: skip it)
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include "kernels/layer_kernels.hpp"

namespace {

using hkf_estimator::LayerKernels;

int failures = 0;

void expect(bool ok, const char *level, const char *what, double error)
{
    std::printf("%-7s %-58s %s (error %.2e)\n", level, what, ok ? "ok" : "FAILED", error);
    if (!ok) ++failures;
}

std::vector<float> noise(size_t n, unsigned seed, float spread)
{
    std::mt19937 random(seed);
    std::normal_distribution<float> normal(0.0f, spread);
    std::vector<float> v(n);
    for (float &x : v) x = normal(random);
    return v;
}

// One tile: cin input channels; the packed weights [cin][rows], the bias, an input of `pitch` floats a row;
// with swish, the sum x comes out as x / (1 + exp(-x)); narrow: the one-vector tile.
void check_tile(const LayerKernels &k, int cin, bool swish, bool narrow = false)
{
    const int rows = k.tile_rows, pixels = narrow ? k.narrow_pixels : k.tile_pixels;
    const long pitch = pixels + 7;  // a plane wider than the tile: the tile reads its own pixels only
    const std::vector<float> weights = noise(static_cast<size_t>(cin) * rows, 1, 0.3f), bias = noise(rows, 2, 0.5f);
    const std::vector<float> in = noise(static_cast<size_t>(cin) * pitch, 3, 1.0f);
    std::vector<float> out(static_cast<size_t>(rows) * (pixels + 3), -7.0f);
    const hkf_estimator::PointwiseTile tile{weights.data(), cin, in.data(), pitch, bias.data(), out.data(), pixels + 3, swish};
    (narrow ? k.pointwise_tile_narrow : k.pointwise_tile)(tile);
    double worst = 0.0, scale = 1e-6;
    bool outside = true;
    for (int r = 0; r < rows; ++r) {
        for (int p = 0; p < pixels; ++p) {
            double sum = bias[r];
            for (int c = 0; c < cin; ++c) sum += static_cast<double>(weights[static_cast<size_t>(c) * rows + r]) * in[c * pitch + p];
            if (swish) sum /= 1.0 + std::exp(-sum);
            worst = std::fmax(worst, std::fabs(out[static_cast<size_t>(r) * (pixels + 3) + p] - sum));
            scale = std::fmax(scale, std::fabs(sum));
        }
        for (int p = pixels; p < pixels + 3; ++p) outside = outside && out[static_cast<size_t>(r) * (pixels + 3) + p] == -7.0f;
    }
    char what[80];
    std::snprintf(what, sizeof what, "pointwise tile %d x %d, %d input channels%s", rows, pixels, cin,
                  swish ? ", swish" : "");
    expect(worst / scale < 1e-5 && outside, k.name, what, worst / scale);
}

// count columns (a plane's last pixels, each its input channels repeated once per row) against the same packed
// weights; cin chosen so that cin x rows ends in part of the kernel's span of sums, or does not.
void check_columns(const LayerKernels &k, int cin, int count, bool swish)
{
    const int rows = k.tile_rows;
    const std::vector<float> weights = noise(static_cast<size_t>(cin) * rows, 7, 0.3f), bias = noise(rows, 8, 0.5f);
    const std::vector<float> in = noise(static_cast<size_t>(cin) * count, 9, 1.0f);  // [column][channel]
    std::vector<float> columns;
    for (int p = 0; p < count; ++p)
        for (int c = 0; c < cin; ++c) columns.insert(columns.end(), rows, in[static_cast<size_t>(p) * cin + c]);
    std::vector<float> sums(static_cast<size_t>(count) * rows + 3, -7.0f);
    k.pointwise_columns(hkf_estimator::PointwiseColumns{weights.data(), cin, columns.data(), count, bias.data(), sums.data(), swish});
    double worst = 0.0, scale = 1e-6;
    for (int p = 0; p < count; ++p)
        for (int r = 0; r < rows; ++r) {
            double sum = bias[r];
            for (int c = 0; c < cin; ++c) sum += static_cast<double>(weights[static_cast<size_t>(c) * rows + r]) * in[static_cast<size_t>(p) * cin + c];
            if (swish) sum /= 1.0 + std::exp(-sum);
            worst = std::fmax(worst, std::fabs(sums[static_cast<size_t>(p) * rows + r] - sum));
            scale = std::fmax(scale, std::fabs(sum));
        }
    const bool outside = sums[sums.size() - 3] == -7.0f;
    char what[80];
    std::snprintf(what, sizeof what, "pointwise columns %d x %d, %d input channels%s", rows, count, cin, swish ? ", swish" : "");
    expect(worst / scale < 1e-5 && outside, k.name, what, worst / scale);
}

void check_taps(const LayerKernels &k, int kernel, int stride, hkf_estimator::DepthwiseTaps *taps)
{
    const int pitch = 23, count = 5 * pitch;
    const long phase_size = static_cast<long>(pitch) * (5 + (kernel - 1) / stride + 1);
    const std::vector<float> phases = noise(static_cast<size_t>(stride) * stride * phase_size, 4, 1.0f);
    const std::vector<float> weights = noise(static_cast<size_t>(kernel) * kernel, 5, 0.3f);
    std::vector<float> sum(count);
    taps(hkf_estimator::PhasePlanes{phases.data(), phase_size, pitch}, weights.data(), 0.25f, sum.data(), count);
    double worst = 0.0;
    for (int j = 0; j < count; ++j) {
        double expected = 0.25;
        for (int ky = 0; ky < kernel; ++ky)
            for (int kx = 0; kx < kernel; ++kx)
                expected += static_cast<double>(weights[ky * kernel + kx]) *
                            phases[((ky % stride) * stride + kx % stride) * phase_size + (ky / stride) * pitch + kx / stride + j];
        worst = std::fmax(worst, std::fabs(sum[j] - expected));
    }
    char what[80];
    std::snprintf(what, sizeof what, "depthwise taps %dx%d, stride %d", kernel, kernel, stride);
    expect(worst < 1e-5, k.name, what, worst);
}

// An activation's inputs: [-200, 200] in steps of 0.01, and +-1e5.
std::vector<float> activation_inputs()
{
    std::vector<float> x;
    for (int i = -20000; i <= 20000; ++i) x.push_back(static_cast<float>(i) * 0.01f);
    x.push_back(-1e5f);
    x.push_back(1e5f);
    return x;
}

void check_swish_and_mean(const LayerKernels &k)
{
    const std::vector<float> x = activation_inputs();
    std::vector<float> y(x.size());
    k.swish(x.data(), y.data(), static_cast<long>(x.size()));
    double worst = 0.0;
    for (size_t i = 0; i < x.size(); ++i) {
        const double expected = x[i] / (1.0 + std::exp(-static_cast<double>(x[i])));
        worst = std::fmax(worst, std::fabs(y[i] - expected) / std::fmax(1.0, std::fabs(expected)));
    }
    expect(worst < 5e-7, k.name, "swish on [-200, 200] and +-1e5", worst);
    const std::vector<float> plane = noise(49 * 3 + 5, 6, 2.0f);
    double sum = 0.0;
    for (float v : plane) sum += v;
    const double mean_error = std::fabs(k.plane_mean(plane.data(), static_cast<long>(plane.size())) - sum / plane.size());
    expect(mean_error < 1e-6, k.name, "a plane's mean (152 floats)", mean_error);
}

// Rows of n floats scaled, one factor a row, from one pitch to another (a gated pixel tile): each product
// exactly the float product, and nothing written past a row's n floats.
void check_scale_rows(const LayerKernels &k, long n)
{
    const long rows = 5, src_pitch = 53, dst_pitch = n + 3;
    const std::vector<float> src = noise(rows * src_pitch, 7, 1.0f), scales = noise(rows, 8, 1.0f);
    std::vector<float> dst(rows * dst_pitch, -7.0f);
    k.scale_rows(hkf_estimator::ScaledRows{src.data(), src_pitch, scales.data(), dst.data(), dst_pitch, rows, n});
    long wrong = 0;
    for (long r = 0; r < rows; ++r)
        for (long i = 0; i < dst_pitch; ++i)
            wrong += dst[r * dst_pitch + i] != (i < n ? src[r * src_pitch + i] * scales[r] : -7.0f);
    char what[80];
    std::snprintf(what, sizeof what, "scaled rows of %ld floats", n);
    expect(wrong == 0, k.name, what, static_cast<double>(wrong));
}

// y += x's rows of a summed (a squeeze-and-excitation's product: 1152 -> 48 and 48 -> 1152, 5 -> 37 past the vectors)
// against a sum in double, relative to y's largest magnitude.
void check_accumulate_rows(const LayerKernels &k, long rows, long n)
{
    const std::vector<float> a = noise(rows * n, 9, 0.3f), x = noise(rows, 10, 1.0f), start = noise(n, 11, 0.5f);
    std::vector<float> y = start;
    k.accumulate_rows(a.data(), n, x.data(), rows, n, y.data());
    double worst = 0.0, scale = 1e-6;
    for (long j = 0; j < n; ++j) {
        double sum = start[j];
        for (long i = 0; i < rows; ++i) sum += static_cast<double>(a[i * n + j]) * x[i];
        worst = std::fmax(worst, std::fabs(y[j] - sum));
        scale = std::fmax(scale, std::fabs(sum));
    }
    char what[80];
    std::snprintf(what, sizeof what, "rows accumulated, %ld x %ld", rows, n);
    expect(worst / scale < 1e-5, k.name, what, worst / scale);
}

void check_sigmoid(const LayerKernels &k)
{
    const std::vector<float> x = activation_inputs();
    std::vector<float> y(x.size());
    k.sigmoid(x.data(), y.data(), static_cast<long>(x.size()));
    double worst = 0.0;  // relative; absolute below 1e-30, where a float's exp is clamped (about 6e-39 for x < -88)
    for (size_t i = 0; i < x.size(); ++i) {
        const double expected = 1.0 / (1.0 + std::exp(-static_cast<double>(x[i])));
        worst = std::fmax(worst, std::fabs(y[i] - expected) / std::fmax(expected, 1e-30));
    }
    expect(worst < 5e-7, k.name, "sigmoid on [-200, 200] and +-1e5", worst);
}

bool cpu_runs(const LayerKernels &k)
{
#if defined(__x86_64__)
    __builtin_cpu_init();
    if (k.level == hkf_estimator::SimdLevel::avx512) return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("fma");
    if (k.level == hkf_estimator::SimdLevel::avx2) return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    if (k.level == hkf_estimator::SimdLevel::avx) return __builtin_cpu_supports("avx");
#endif
    return k.level == hkf_estimator::SimdLevel::baseline;
}

}  // namespace

int main(int argc, char **argv)
{
    std::vector<const LayerKernels *> levels = {&hkf_estimator::kBaselineKernels};
#if defined(__x86_64__)
    levels.insert(levels.begin(), {&hkf_estimator::kAvx512Kernels, &hkf_estimator::kAvx2Kernels, &hkf_estimator::kAvxKernels});
#endif
    int tested = 0;
    for (const LayerKernels *k : levels) {
        bool asked = argc < 2;
        for (int i = 1; i < argc; ++i) asked = asked || std::strcmp(argv[i], k->name) == 0;
        if (!asked) continue;
        if (!cpu_runs(*k)) {
            std::printf("%-7s skipped: this CPU cannot run it\n", k->name);
            continue;
        }
        for (int cin : {1, 3, 16, 240}) check_tile(*k, cin, false);
        for (int cin : {3, 240}) check_tile(*k, cin, true);
        for (int cin : {1, 240}) check_tile(*k, cin, cin > 1, true);
        for (int cin : {1, 5, 16, 1152, 1153}) check_columns(*k, cin, 1 + cin % 2, cin == 5);
        check_columns(*k, 16, 1, true);
        check_taps(*k, 3, 1, k->taps_3x3_stride1);
        check_taps(*k, 3, 2, k->taps_3x3_stride2);
        check_taps(*k, 5, 1, k->taps_5x5_stride1);
        check_taps(*k, 5, 2, k->taps_5x5_stride2);
        check_swish_and_mean(*k);
        for (long n : {3L, 32L, 37L}) check_scale_rows(*k, n);
        check_accumulate_rows(*k, 1152, 48);
        check_accumulate_rows(*k, 48, 1152);
        check_accumulate_rows(*k, 5, 37);
        check_sigmoid(*k);
        ++tested;
    }
    std::printf("test_layer_kernels: %d levels tested, %d failures\n", tested, failures);
    return failures == 0 && tested > 0 ? 0 : 1;
}
